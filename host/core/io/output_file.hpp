// How an output file the user named is replaced (docs/export.md): only by a complete file.
// Each output is written under a temporary name in the same folder (so the rename never
// crosses a file system) and renamed over the name once it is complete and closed; if
// anything fails first, the temporary is removed and the old file, if any, is untouched.
//
// Temporaries are created exclusively (mkstemp: O_CREAT|O_EXCL, so a symlink or any file
// already at the name is never followed or reused) under an unguessable name, and a SIGINT or
// SIGTERM removes every temporary still pending before the process ends.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <functional>
#include <string>
#include <utility>

namespace clothsim {

// Creates an empty temporary for `path` in its folder, `NAME.XXXXXX.tmp` with six random
// characters, exclusively, with the permissions a new file gets (0666 less the umask), and
// registers it for removal on SIGINT/SIGTERM. Throws std::runtime_error naming `path`.
std::string create_temporary(const std::string& path);

// Renames `from` over `to` (atomically, on the same file system; a symlink at `to` is
// replaced, not followed); throws std::runtime_error naming `to` if it fails, after removing
// `from`.
void replace_file(const std::string& from, const std::string& to);

// Removes `path` if it exists (a symlink itself, never its target); never throws. Also
// forgets it as a temporary to remove on a signal.
void remove_quietly(const std::string& path);

// Installs the SIGINT/SIGTERM handler that removes the pending temporaries (and stops the
// child processes writing them) and then ends the process as the signal would. main() calls it
// once, first.
void remove_temporaries_on_signals();

// A child process writing a temporary (ffmpeg): stopped, and waited for, before a signal
// removes the temporaries, so it cannot create one again after. forget_writer when it ended.
void register_writer(pid_t pid);
void forget_writer(pid_t pid);

// Writes the text file `path` whole: `body` prints into the stream of a PendingFile's
// temporary; every write and the close are checked, then the temporary is renamed over `path`.
// Throws std::runtime_error naming `path` (and nothing is left behind).
void write_text_file(const std::string& path, const std::function<void(std::FILE*)>& body);

// The temporary of one output: commit() renames it over the destination; destroyed without
// commit (an exception, an early return), it removes the temporary.
class PendingFile {
 public:
  explicit PendingFile(std::string path) : path_(std::move(path)), temp_(create_temporary(path_)) {}
  ~PendingFile() {
    if (!done_) remove_quietly(temp_);
  }
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::string& path() const { return path_; }  // the destination
  const std::string& temp() const { return temp_; }  // what to write to
  void commit() { commit_as(path_); }
  // Renames the temporary to `other` instead (a PC2 kept as NAME.pc2.partial).
  void commit_as(const std::string& other) {
    done_ = true;
    replace_file(temp_, other);
  }
  void discard() {
    done_ = true;
    remove_quietly(temp_);
  }

 private:
  std::string path_, temp_;
  bool done_ = false;
};

// Writes `path` through `write(temporary)`, then renames the temporary over it; if `write`
// throws, the temporary is removed and the exception passes on.
template <class Write> void write_replacing(const std::string& path, Write&& write) {
  PendingFile file(path);
  write(file.temp());
  file.commit();
}

// Writes `text` (bytes as they are) to `path` through write_replacing; throws
// std::runtime_error naming `path` if it cannot be written or replaced.
void write_text_replacing(const std::string& path, const std::string& text);

}  // namespace clothsim

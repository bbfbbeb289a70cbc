// How an output file the user named is replaced (docs/export.md): only by a complete file.
// Each output is written under a temporary name in the same folder (so the rename never
// crosses a file system) and renamed over the name once it is complete and closed; if
// anything fails first, the temporary is removed and the old file, if any, is untouched.
#pragma once

#include <string>
#include <utility>

namespace clothsim {

// Where the new version of `path` is written: `NAME.PID.tmp` in the folder of `path` (the
// process id keeps two runs apart; the folder keeps the rename atomic).
std::string temporary_path(const std::string& path);

// Renames `from` over `to` (atomically, on the same file system); throws std::runtime_error
// naming `to` if the rename fails, after removing `from`.
void replace_file(const std::string& from, const std::string& to);

// Removes `path` if it exists; never throws.
void remove_quietly(const std::string& path);

// The temporary of one output: commit() renames it over the destination; destroyed without
// commit (an exception, an early return), it removes the temporary.
class PendingFile {
 public:
  explicit PendingFile(std::string path) : path_(std::move(path)), temp_(temporary_path(path_)) {}
  ~PendingFile() {
    if (!done_) remove_quietly(temp_);
  }
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::string& path() const { return path_; }  // the destination
  const std::string& temp() const { return temp_; }  // what to write to
  void commit() {
    done_ = true;
    replace_file(temp_, path_);
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

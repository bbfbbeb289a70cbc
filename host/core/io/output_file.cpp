#include "io/output_file.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace clothsim {
namespace fs = std::filesystem;
namespace {

// The temporaries a signal must remove. A signal handler may not allocate or lock, so they are
// kept in fixed slots it can read as they are: 0 free, 1 being filled, 2 a live path.
constexpr int kSlots = 256;
constexpr size_t kPathBytes = 4096;  // PATH_MAX on Linux: no longer path can be opened
struct Slot {
  std::atomic<int> state{0};
  char path[kPathBytes];
};
Slot g_slots[kSlots];
constexpr int kWriters = 16;
std::atomic<pid_t> g_writers[kWriters];

void remember(const std::string& path) {
  if (path.size() >= kPathBytes) return;
  for (Slot& s : g_slots) {
    int free = 0;
    if (!s.state.compare_exchange_strong(free, 1)) continue;
    std::memcpy(s.path, path.c_str(), path.size() + 1);
    s.state.store(2);
    return;
  }
  // Over 256 outputs pending at once: none does; the file is still removed on any other exit.
}

void forget(const std::string& path) {
  for (Slot& s : g_slots) {
    if (s.state.load() != 2 || path != s.path) continue;
    int live = 2;
    s.state.compare_exchange_strong(live, 0);
    return;
  }
}

extern "C" void remove_and_reraise(int sig) {
  // Only async-signal-safe calls: kill, waitpid, unlink, signal, raise. A writer is stopped
  // and reaped first, so it cannot create its file again after the unlink.
  for (auto& w : g_writers) {
    const pid_t pid = w.exchange(0);
    if (pid <= 0) continue;
    kill(pid, SIGKILL);
    while (waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  for (Slot& s : g_slots)
    if (s.state.load() == 2) unlink(s.path);
  signal(sig, SIG_DFL);
  raise(sig);  // ends the process as the signal would have: the parent sees the same status
}

mode_t new_file_mode() {
  // umask can only be read by setting it; done once, before any thread makes files.
  static const mode_t mode = [] {
    const mode_t mask = umask(022);
    umask(mask);
    return mode_t(0666 & ~mask);
  }();
  return mode;
}

}  // namespace

std::string create_temporary(const std::string& path) {
  const fs::path p(path);
  // NAME.XXXXXX.tmp, with NAME shortened so the whole stays within a file name's 255 bytes.
  std::string stem = p.filename().string().substr(0, 200);
  std::string pattern = (p.parent_path() / (stem + ".XXXXXX.tmp")).string();
  // A signal between creating the file and remembering it would leave it: held off till both are done.
  sigset_t stop, old;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, &old);
  const int fd = mkostemps(pattern.data(), 4, O_CLOEXEC);
  const int error = errno;
  if (fd >= 0) remember(pattern);
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  if (fd < 0)
    throw std::runtime_error(
        fmt::format("{}: cannot create a temporary file beside it ({})", path, std::strerror(error)));
  fchmod(fd, new_file_mode());  // mkstemp makes 0600; a finished output gets the usual permissions
  close(fd);
  return pattern;
}

void replace_file(const std::string& from, const std::string& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    remove_quietly(from);
    throw std::runtime_error(fmt::format("{}: cannot replace it with the new file ({})", to, ec.message()));
  }
  forget(from);
}

void write_text_replacing(const std::string& path, const std::string& text) {
  write_replacing(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write it", path));
  });
}

void remove_quietly(const std::string& path) {
  unlink(path.c_str());  // the name itself: a symlink is removed, never followed
  forget(path);
}

void remove_temporaries_on_signals() {
  new_file_mode();
  struct sigaction sa {};
  sa.sa_handler = remove_and_reraise;
  sigemptyset(&sa.sa_mask);
  sigaddset(&sa.sa_mask, SIGINT);  // one handler at a time: the second signal waits, then ends it
  sigaddset(&sa.sa_mask, SIGTERM);
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;  // started ignoring it (nohup, a background job): keep that
    sigaction(sig, &sa, nullptr);
  }
}

void register_writer(pid_t pid) {
  for (auto& w : g_writers) {
    pid_t free = 0;
    if (w.compare_exchange_strong(free, pid)) return;
  }
}

void forget_writer(pid_t pid) {
  for (auto& w : g_writers) {
    pid_t mine = pid;
    if (w.compare_exchange_strong(mine, 0)) return;
  }
}

void write_text_file(const std::string& path, const std::function<void(std::FILE*)>& body) {
  PendingFile out(path);
  std::FILE* f = std::fopen(out.temp().c_str(), "w");
  if (!f) throw std::runtime_error(fmt::format("{}: cannot open for writing ({})", path, std::strerror(errno)));
  // Closed on every path: fmt::print throws when a write fails (a full disk).
  struct Closer {
    std::FILE*& f;
    ~Closer() { if (f) std::fclose(f); }
  } closer{f};
  body(f);
  const bool ok = !std::ferror(f);
  const bool closed = std::fclose(std::exchange(f, nullptr)) == 0;
  if (!ok || !closed) throw std::runtime_error(fmt::format("{}: write failed", path));
  out.commit();
}

}  // namespace clothsim

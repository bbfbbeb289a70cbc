#include "io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

namespace clothsim {

// The two a hostile path provokes most also give their name.
std::string errno_words(int e) {
  switch (e) {
    case ENOENT: return "does not exist";
    case ELOOP: return "a loop of symbolic links (ELOOP: too many levels of symbolic links)";
    case ENAMETOOLONG: return "the name is too long (ENAMETOOLONG)";
    case ENOTDIR: return "a part of the path is not a directory";
    case EACCES: return "permission denied";
    default: return std::strerror(e);
  }
}

std::string file_kind(unsigned mode) {
  return S_ISREG(mode)    ? "a regular file"
         : S_ISDIR(mode)  ? "a directory"
         : S_ISFIFO(mode) ? "a FIFO (named pipe)"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a plain file";
}

namespace {

std::optional<std::string> kind_problem(mode_t mode) {
  if (S_ISREG(mode)) return std::nullopt;
  return fmt::format("is {}, not a regular file", file_kind(mode));
}

}  // namespace

std::optional<std::string> input_file_problem(const std::filesystem::path& path, uint64_t* size) {
  if (path.empty()) return std::string("an empty path (expected the name of a file)");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return errno_words(errno);
  if (auto k = kind_problem(st.st_mode)) return k;
  if (size) *size = uint64_t(st.st_size);
  return std::nullopt;
}

std::string read_input_file(const std::filesystem::path& path, uint64_t max_bytes) {
  uint64_t size = 0;
  if (auto p = input_file_problem(path, &size)) throw std::runtime_error(*p);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(errno_words(errno));
  struct stat st {};
  std::string out;
  try {
    if (::fstat(fd, &st) != 0) throw std::runtime_error(errno_words(errno));
    if (auto k = kind_problem(st.st_mode)) throw std::runtime_error(*k);
    if (uint64_t(st.st_size) > max_bytes)
      throw std::runtime_error(fmt::format("{} bytes, more than the {} accepted", uint64_t(st.st_size), max_bytes));
    out.resize(size_t(st.st_size));
    size_t got = 0;
    while (got < out.size()) {
      const ssize_t n = ::read(fd, out.data() + got, out.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw std::runtime_error(fmt::format("read failed ({})", std::strerror(errno)));
      if (n == 0) break;  // shrank since the fstat: what is there
      got += size_t(n);
    }
    out.resize(got);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return out;
}

std::string printable(std::string_view s, bool keep_newlines) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && !(keep_newlines && c == '\n')) || c == 0x7f) out += fmt::format("\\x{:02x}", c);
    else out += ch;
  }
  return out;
}

}  // namespace clothsim

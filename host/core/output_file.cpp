#include "output_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

namespace clothsim {
namespace fs = std::filesystem;

std::string temporary_path(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / fmt::format("{}.{}.tmp", p.filename().string(), getpid())).string();
}

void replace_file(const std::string& from, const std::string& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    remove_quietly(from);
    throw std::runtime_error(fmt::format("{}: cannot replace it with the new file ({})", to, ec.message()));
  }
}

void remove_quietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace clothsim

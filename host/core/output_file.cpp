#include "output_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
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

void write_text_replacing(const std::string& path, const std::string& text) {
  write_replacing(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write it", path));
  });
}

void remove_quietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace clothsim

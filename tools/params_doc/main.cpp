// clothsim-params-doc: prints docs/parameters.md as the parameter table makes it,
// --write FILE writes it, --check FILE fails when the committed FILE differs (a ctest test).
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/output_file.hpp"
#include "scene/param_doc.hpp"

namespace {

constexpr const char* kRegenerate = "cmake --build build --target parameters-doc";

int check(const char* path, const std::string& want) {
  std::ifstream in(path, std::ios::binary);
  const std::string got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in && got == want) {
    std::printf("%s is up to date\n", path);
    return 0;
  }
  std::fprintf(stderr, "docs/parameters.md is out of date (%s differs from the parameter table in "
               "host/core/scene/scene_table.cpp); regenerate with: %s\n", path, kRegenerate);
  // The first line that differs, so the cause is visible in the test log.
  std::istringstream a(got), b(want);
  std::string la, lb;
  for (int line = 1; std::getline(b, lb); ++line) {
    if (!std::getline(a, la)) la = "(end of file)";
    if (la != lb) {
      std::fprintf(stderr, "  line %d\n  committed: %s\n  generated: %s\n", line, la.c_str(), lb.c_str());
      break;
    }
  }
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string md = clothsim::parameters_markdown();
  const std::string mode = argc == 3 ? argv[1] : "";
  if (argc == 1) {
    std::fputs(md.c_str(), stdout);
    return 0;
  }
  if (mode == "--check") return check(argv[2], md);
  if (mode == "--write") {
    // Beside the named file first and renamed once complete (output_file.hpp).
    try {
      clothsim::write_text_replacing(argv[2], md);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    }
    std::printf("wrote %s\n", argv[2]);
    return 0;
  }
  std::fprintf(stderr, "usage: clothsim-params-doc [--check FILE | --write FILE]\n");
  return 2;
}

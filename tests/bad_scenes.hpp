// The malformed-scene corpus: tests/scenes_bad/expected.txt lists "file.json<TAB>substring the
// error must contain" ('#' starts a comment). Shared by the loader and the CLI tests.
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::test {

inline const std::filesystem::path kBadScenes = std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "tests" / "scenes_bad";

inline std::vector<std::pair<std::string, std::string>> read_bad_scene_manifest() {
  std::ifstream in(kBadScenes / "expected.txt");
  REQUIRE(in);
  std::vector<std::pair<std::string, std::string>> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    auto tab = line.find('\t');
    REQUIRE(tab != std::string::npos);
    out.emplace_back(line.substr(0, tab), line.substr(tab + 1));
  }
  return out;
}

}  // namespace clothsim::test

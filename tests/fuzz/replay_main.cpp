// Replays fuzz inputs through the scene-loader fuzz target without libFuzzer, so that the
// regression inputs and the seed corpus are checked by ctest in every build (also the
// sanitizer build).
//
//   clothsim_fuzz_scene_replay [--expect MANIFEST] [--generated] [FILE|DIR]...
//
// Every FILE, and every file directly inside a DIR, must satisfy the property of
// fuzz_scene.cpp (a violation aborts). With --expect, MANIFEST lists
// "file<TAB>loads" or "file<TAB>rejected<TAB>substring of the SceneError message" for the
// files of its own directory ('#' starts a comment); each must have that outcome, and every
// other file in that directory (but *.md and the manifest) must be listed. --generated adds
// the regression inputs too large to keep as files (generated_cases() below).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_scene.hpp"

namespace fs = std::filesystem;

namespace {

clothsim::fuzz::Outcome replay(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", file.string().c_str());
    std::exit(2);
  }
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return clothsim::fuzz::run_one(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

struct Case {
  std::string name, bytes, expected;  // expected: a substring of the SceneError message
};

// Regression inputs of a few hundred kilobytes, made here instead of kept in git.
std::vector<Case> generated_cases() {
  const std::string scene = R"({"cloth": {"width": 1, "height": 1, "num_width_points": 8, "num_height_points": 6,
                                          "thickness": 0.0095, "orientation": 0}})";
  const size_t deep = 100000;  // 70,000 '[' overflowed the 8 MiB stack when the value was dumped
  std::vector<Case> cases;
  // Found by review: describing (dumping) or copying a deeply nested value recursed once per
  // level, so a scene file or a --set value of ~70,000 nested arrays crashed with SIGSEGV.
  cases.push_back({"a scene file nested 100,000 arrays deep",
                   R"({"cloth": )" + std::string(deep, '[') + std::string(deep, ']') + "}",
                   "<fuzz>: arrays and objects nested deeper than 32 levels"});
  cases.push_back({"a --set value nested 100,000 arrays deep",
                   scene + std::string(1, '\0') + "cloth.width=" + std::string(deep, '[') + std::string(deep, ']'),
                   "<fuzz>: --set cloth.width=[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["});
  cases.push_back({"a --set value of 100,000 unclosed arrays",
                   scene + std::string(1, '\0') + "simulation.gravity=" + std::string(deep, '['),
                   "arrays and objects nested deeper than 32 levels"});
  std::string path = "simulation.gravity";
  for (int i = 0; i < 60000; ++i) path += ".a";
  cases.push_back({"a --set key path 60,000 keys deep", scene + std::string(1, '\0') + path + "=1",
                   "a key path of more than 32 parts"});
  return cases;
}

}  // namespace

int main(int argc, char** argv) {
  int inputs = 0, loaded = 0, failures = 0;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--generated") {
      for (const Case& c : generated_cases()) {
        const auto out = clothsim::fuzz::run_one(reinterpret_cast<const uint8_t*>(c.bytes.data()), c.bytes.size());
        ++inputs;
        loaded += out.loaded;
        if (out.loaded || out.error.find(c.expected) == std::string::npos) {
          std::fprintf(stderr, "FAIL %s: expected a SceneError containing '%s', got: %.200s\n", c.name.c_str(),
                       c.expected.c_str(), out.loaded ? "(loaded)" : out.error.c_str());
          ++failures;
        } else {
          std::printf("ok   %s: %.120s\n", c.name.c_str(), out.error.c_str());
        }
      }
      continue;
    }
    if (arg == "--expect" && a + 1 < argc) {
      const fs::path manifest = argv[++a];
      std::ifstream in(manifest);
      if (!in) {
        std::fprintf(stderr, "replay: cannot read %s\n", manifest.string().c_str());
        return 2;
      }
      std::map<std::string, bool> listed;
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string part; std::getline(ss, part, '\t');) f.push_back(part);
        const bool want_load = f.size() == 2 && f[1] == "loads";
        if (!want_load && !(f.size() == 3 && f[1] == "rejected")) {
          std::fprintf(stderr, "replay: %s: bad line: %s\n", manifest.string().c_str(), line.c_str());
          return 2;
        }
        listed[f[0]] = true;
        const auto out = replay(manifest.parent_path() / f[0]);
        ++inputs;
        loaded += out.loaded;
        if (want_load && !out.loaded) {
          std::fprintf(stderr, "FAIL %s: expected to load, got: %s\n", f[0].c_str(), out.error.c_str());
          ++failures;
        } else if (!want_load && (out.loaded || out.error.find(f[2]) == std::string::npos)) {
          std::fprintf(stderr, "FAIL %s: expected a SceneError containing '%s', got: %s\n", f[0].c_str(), f[2].c_str(),
                       out.loaded ? "(loaded)" : out.error.c_str());
          ++failures;
        } else {
          std::printf("ok   %s: %s\n", f[0].c_str(), out.loaded ? "loads" : out.error.c_str());
        }
      }
      for (const auto& e : fs::directory_iterator(manifest.parent_path())) {
        const std::string name = e.path().filename().string();
        if (e.is_regular_file() && e.path() != manifest && e.path().extension() != ".md" && !listed.count(name)) {
          std::fprintf(stderr, "FAIL %s: not listed in %s\n", name.c_str(), manifest.string().c_str());
          ++failures;
        }
      }
      continue;
    }
    std::vector<fs::path> files;
    if (fs::is_directory(arg)) {
      for (const auto& e : fs::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.push_back(arg);
    }
    for (const auto& f : files) {
      const auto out = replay(f);  // aborts on a property violation
      ++inputs;
      loaded += out.loaded;
    }
  }
  std::printf("replay: %d inputs, %d loaded, %d rejected with a SceneError, %d failed\n", inputs, loaded,
              inputs - loaded, failures);
  return failures == 0 && inputs > 0 ? 0 : 1;
}

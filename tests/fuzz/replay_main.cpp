// Replays fuzz inputs through a fuzz target without libFuzzer, so that the regression inputs
// and the seed corpora are checked by ctest in every build (also the sanitizer build).
//
//   clothsim_fuzz_replay --target scene|state|pc2 [--expect MANIFEST] [--generated] [--load DIR]
//                        [--reject DIR] [FILE|DIR]...
//
// Every input must satisfy the property of the target's file (fuzz_scene.cpp, fuzz_state.cpp,
// fuzz_pc2.cpp; a violation aborts), and:
//   --expect MANIFEST  lists "file<TAB>loads" or "file<TAB>rejected<TAB>substring of the
//                      loader's error message" for the files of its own directory ('#' starts
//                      a comment); each must have that outcome, and every other file there (but
//                      *.md and the manifest) must be listed;
//   --generated        the scene loader's regression inputs too large to keep as files
//                      (replay_generated());
//   --load DIR         every *.json directly inside DIR must load (scene);
//   --reject DIR       every *.json directly inside DIR must be rejected with a SceneError (scene);
//   FILE, DIR          a file, or every file directly inside DIR: the property only.
// Exit 0 when every input had its outcome and there was at least one input.
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "fuzz_targets.hpp"

namespace fs = std::filesystem;

namespace {

// The input being run, named when the target aborts on a property violation.
std::string g_current;

struct Target {
  const char* name;
  clothsim::fuzz::Outcome (*run)(const uint8_t*, size_t);
  const char* error_type;  // what a rejection throws, for messages
};
constexpr Target kTargets[] = {
    {"scene", clothsim::fuzz::run_scene, "SceneError"},
    {"state", clothsim::fuzz::run_state, "CheckpointError"},
    {"pc2", clothsim::fuzz::run_pc2, "Pc2Error"},
};

void name_the_input_on_abort(int) {
  const std::string msg = "replay: the input that aborted: " + g_current + "\n";
  (void)!write(STDERR_FILENO, msg.data(), msg.size());
  std::signal(SIGABRT, SIG_DFL);  // then abort as before, so the test fails
}

// What an input must do: load, or be rejected with a message containing `message`.
struct Want {
  bool load = false;
  std::string message;  // for a rejection; empty matches any error of the target's type
};

struct Tally {
  const Target* target = nullptr;
  int inputs = 0, loaded = 0, failures = 0;

  // Runs one input (the target aborts on a property violation) and checks the outcome, if any.
  void run(const std::string& name, const std::string& bytes, const std::optional<Want>& want) {
    g_current = name;
    const auto out = target->run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    ++inputs;
    loaded += out.loaded;
    if (!want) return;
    const std::string got = out.loaded ? "(loaded)" : out.error;
    const bool ok = want->load ? out.loaded : !out.loaded && out.error.find(want->message) != std::string::npos;
    if (ok) {
      std::printf("ok   %s: %.120s\n", name.c_str(), out.loaded ? "loads" : out.error.c_str());
      return;
    }
    if (want->load)
      std::fprintf(stderr, "FAIL %s: expected to load, got: %.200s\n", name.c_str(), got.c_str());
    else
      std::fprintf(stderr, "FAIL %s: expected a %s containing '%s', got: %.200s\n", name.c_str(),
                   target->error_type, want->message.c_str(), got.c_str());
    ++failures;
  }
};

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", file.string().c_str());
    std::exit(2);
  }
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The regular files directly inside `dir` (only those ending in `ext` when it is given), sorted.
std::vector<fs::path> files_in(const fs::path& dir, const std::string& ext = "") {
  if (!fs::is_directory(dir)) {
    std::fprintf(stderr, "replay: %s is not a directory\n", dir.string().c_str());
    std::exit(2);
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && (ext.empty() || e.path().extension() == ext)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void replay_manifest(const fs::path& manifest, Tally& tally) {
  std::ifstream in(manifest);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", manifest.string().c_str());
    std::exit(2);
  }
  std::set<std::string> listed;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string part; std::getline(ss, part, '\t');) f.push_back(part);
    const bool load = f.size() == 2 && f[1] == "loads";
    if (!load && !(f.size() == 3 && f[1] == "rejected" && !f[2].empty())) {
      std::fprintf(stderr, "replay: %s: bad line: %s\n", manifest.string().c_str(), line.c_str());
      std::exit(2);
    }
    listed.insert(f[0]);
    tally.run(f[0], read_bytes(manifest.parent_path() / f[0]), Want{load, load ? "" : f[2]});
  }
  for (const fs::path& p : files_in(manifest.parent_path())) {
    if (p != manifest && p.extension() != ".md" && !listed.count(p.filename().string())) {
      std::fprintf(stderr, "FAIL %s: not listed in %s\n", p.filename().string().c_str(), manifest.string().c_str());
      ++tally.failures;
    }
  }
}

// Regression inputs of a few hundred kilobytes, made here instead of kept in git.
void replay_generated(Tally& tally) {
  const std::string scene = R"({"cloth": {"width": 1, "height": 1, "num_width_points": 8, "num_height_points": 6,
                                          "thickness": 0.0095, "orientation": 0}})";
  const std::string nul(1, '\0');
  const size_t deep = 100000;  // 70,000 '[' overflowed the 8 MiB stack when the value was dumped
  const std::string opened(deep, '['), closed(deep, ']');
  std::string path = "simulation.gravity";
  for (int i = 0; i < 60000; ++i) path += ".a";
  // Found by review: describing (dumping) or copying a deeply nested value recursed once per
  // level, so a scene file or a --set value of ~70,000 nested arrays crashed with SIGSEGV.
  const Want too_deep{false, "<fuzz>: arrays and objects nested deeper than 32 levels"};
  tally.run("a scene file nested 100,000 arrays deep", R"({"cloth": )" + opened + closed + "}", too_deep);
  tally.run("a --set value nested 100,000 arrays deep", scene + nul + "cloth.width=" + opened + closed,
            Want{false, "<fuzz>: --set cloth.width=[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["});
  tally.run("a --set value of 100,000 unclosed arrays", scene + nul + "simulation.gravity=" + opened,
            Want{false, "arrays and objects nested deeper than 32 levels"});
  tally.run("a --set key path 60,000 keys deep", scene + nul + path + "=1",
            Want{false, "a key path of more than 32 parts"});
}

// The target named by "--target NAME" at the start of the arguments, or null.
const Target* target_of(int argc, char** argv) {
  if (argc < 3 || std::string(argv[1]) != "--target") return nullptr;
  for (const Target& t : kTargets)
    if (argv[2] == std::string(t.name)) return &t;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGABRT, name_the_input_on_abort);
  Tally tally;
  tally.target = target_of(argc, argv);
  if (!tally.target) {
    std::fprintf(stderr, "replay: the first arguments must be --target scene, --target state or --target pc2\n");
    return 2;
  }
  const bool scene = tally.target->run == clothsim::fuzz::run_scene;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--generated" && scene) {
      replay_generated(tally);
    } else if (arg == "--expect" && has_value) {
      replay_manifest(argv[++a], tally);
    } else if ((arg == "--load" || arg == "--reject") && has_value && scene) {
      const Want want{arg == "--load", ""};
      for (const fs::path& p : files_in(argv[++a], ".json")) tally.run(p.string(), read_bytes(p), want);
    } else if (arg.rfind("--", 0) == 0) {
      std::fprintf(stderr, "replay: unknown option, missing value or not for --target %s: %s\n", tally.target->name,
                   arg.c_str());
      return 2;
    } else {
      const auto files = fs::is_directory(arg) ? files_in(arg) : std::vector<fs::path>{arg};
      for (const fs::path& p : files) tally.run(p.string(), read_bytes(p), std::nullopt);
    }
  }
  std::printf("replay: %d inputs, %d loaded, %d rejected with a %s, %d failed\n", tally.inputs, tally.loaded,
              tally.inputs - tally.loaded, tally.target->error_type, tally.failures);
  if (tally.inputs == 0) std::fprintf(stderr, "replay: no inputs (a wrong path?)\n");
  return tally.failures == 0 && tally.inputs > 0 ? 0 : 1;
}

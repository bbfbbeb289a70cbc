// What the output tests (test_outputs.cpp, test_output_safety.cpp) run: the built binary through
// a shell line of the test's own making, and a tiny cloth that runs in milliseconds.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "file_support.hpp"

namespace clothsim::test {

// `clothsim ARGS` under a 60 s timeout (a run that blocks on a FIFO fails instead of hanging the
// suite), stdout and stderr together in *output; `env` goes before it ("XDG_CACHE_HOME=...").
inline int run_binary(const std::string& args, std::string* output = nullptr, const std::string& env = "") {
  const auto log = std::filesystem::temp_directory_path() / fmt::format("clothsim_test_outputs_{}.log", getpid());
  const int status = std::system(
      fmt::format("env {} timeout 60 '{}' {} >'{}' 2>&1 </dev/null", env, CLOTHSIM_BINARY, args, log.string()).c_str());
  if (output) *output = slurp(log);
  std::filesystem::remove(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The pinned2 scene on a 7x5 grid, on the CPU: milliseconds per run.
inline const std::string kSmall = fmt::format(
    "'{}/scenes/pinned2.json' --set cloth.num_width_points=7 --set cloth.num_height_points=5 "
    "--set 'cloth.pinned=[[0,0],[6,0]]' --backend cpu",
    CLOTHSIM_SOURCE_DIR);
// The same cloth far too stiff for its substeps: diverges within a few frames.
inline const std::string kDiverging = kSmall + " --set cloth.ks=1e9 --set simulation.self_collision=false";

}  // namespace clothsim::test

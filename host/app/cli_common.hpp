// Pieces every command shares: exit codes (docs/design.md §3), scene loading from flags,
// terminal progress.
#pragma once

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "backend.hpp"
#include "context.hpp"
#include "io/input_file.hpp"
#include "scene/scene.hpp"

namespace clothsim {

enum ExitCode { kExitOk = 0, kExitCheckFailed = 1, kExitBadInput = 2, kExitNoContext = 3 };

// Thrown by a command to end with a documented exit code and a message for stderr.
struct ExitError : std::runtime_error {
  ExitError(int c, const std::string& m) : std::runtime_error(m), code(c) {}
  int code;
};

// The scene options common to commands that take a scene.
struct SceneOptions {
  std::string path;                // not given: the built-in default; given as "": exit 2
  std::vector<std::string> sets;   // --set key.path=value
  void add_to(CLI::App& cmd, bool positional_required);
  Scene load() const;              // throws SceneError
  CLI::Option* option = nullptr;   // the positional, to tell "" from absent
};

// --no-cache: mesh colliders' fields are built, never read from or kept in the cache folder.
void add_no_cache_flag(CLI::App& cmd);
// Numeric option checks with readable limits ("a number in [0.01, 100]", never DBL_MAX's 309
// digits); each also refuses NaN and infinity by name.
CLI::Validator number_in(double lo, double hi);
CLI::Validator positive_number();      // > 0
CLI::Validator non_negative_number();  // >= 0
CLI::Validator non_empty_path();       // a file option given as "" names no file
// Adds the NaN/infinity check to every numeric option of `app` and its subcommands, the ones
// without a range check included: one place, so no option can forget it.
void refuse_non_finite(CLI::App& app);

enum class BackendKind { Cpu, Gpu };
BackendKind parse_backend(const std::string& name);
// The backend for a scene; the GPU one needs a GL 4.3 context (exit 3 when none).
std::unique_ptr<Backend> make_backend(BackendKind kind, const Scene& scene, const ClothModel& model);
// A headless GL 4.3 context, or ExitError with exit code 3 and what to do.
std::unique_ptr<gl::GlContext> require_headless_context();

// Checks every output of a run before it starts (output_plan.hpp); ExitError 2 naming the
// flag, the file and the problem.
void check_outputs(const class OutputPlan& plan);

// Reads and checks the state file of --load-state, loads it into the backend and returns its
// frame; every failure is ExitError with exit code 2.
int64_t load_state(const std::string& path, const Scene& scene, const ClothModel& model, Backend& backend);

// "frame 120/300  45.1 frames/s  ETA 4 s" on one refreshed line of a terminal; silent when
// stderr is not a TTY so logs and pipes stay clean.
class Progress {
 public:
  Progress(std::string label, int total);
  void update(int done);
  void finish();

 private:
  std::string label_;
  int total_;
  bool tty_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace clothsim

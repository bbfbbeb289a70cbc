// clothsim: command-line entry. Parses, runs one command, maps failures to the exit codes
// of docs/design.md §3.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"
#include "debug_output.hpp"
#include "io/host_memory.hpp"
#include "objects.hpp"
#include "io/output_file.hpp"

int main(int argc, char** argv) {
  using namespace clothsim;
  remove_temporaries_on_signals();  // Ctrl-C or a kill leaves no temporary behind
  CLI::App app{"clothsim: a GPU cloth simulator (OpenGL 4.3 compute shaders) with a CPU reference", "clothsim"};
  app.require_subcommand(0, 1);
  app.failure_message(CLI::FailureMessage::help);  // a usage error shows the usage
  std::function<int()> run;
  add_simulate_command(app, run);
  add_validate_command(app, run);
  add_render_command(app, run);
  add_bench_command(app, run);
  add_static_command(app, run);
  add_sweep_command(app, run);
#ifdef CLOTHSIM_WITH_VIEWER
  add_viewer_options(app, run);
#else
  app.require_subcommand(1);  // the headless build has no viewer to default to
#endif
  refuse_non_finite(app);  // every numeric option of every command, after all are added
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and usage
    return kExitBadInput;
  }
  // Messages quote names read from files (keys, mesh paths, a state's scene name): printable()
  // escapes their control characters so no file can drive the terminal.
  auto say = [](const char* what) { fmt::print(stderr, "error: {}\n", printable(what, /*keep_newlines=*/true)); };
  try {
    return run();
  } catch (const SceneError& e) {
    say(e.what());
    return kExitBadInput;
  } catch (const HostOutOfMemory& e) {
    say(e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    // An allocation without its own HostOutOfMemory: too large an input all the same.
    say("out of host memory (std::bad_alloc): the scene needs more memory than this machine gives; use fewer "
        "points (cloth.num_width_points, cloth.num_height_points) or a smaller mesh");
    return kExitBadInput;
  } catch (const gl::OutOfMemoryError& e) {
    // Like a grid too large for the GPU's limits (docs/design.md section 4): too large an input.
    say(fmt::format("{}\n  The cloth does not fit in this GPU's memory: use fewer points "
                    "(cloth.num_width_points, cloth.num_height_points), close other programs using the GPU, or run "
                    "on the CPU: --backend cpu",
                    e.what()).c_str());
    return kExitBadInput;
  } catch (const gl::GlError& e) {
    // glGetError reported an error during a GPU run (checked once per frame, in release builds
    // too): the run's own check failed, so exit 1 like a divergence; 2 stays bad input.
    say(fmt::format("{}\n  A GL call failed: a bug in clothsim or in the GPU driver, not in the scene. The CPU "
                    "reference computes the same model: --backend cpu",
                    e.what()).c_str());
    return kExitCheckFailed;
  } catch (const ExitError& e) {
    say(e.what());
    return e.code;
  } catch (const std::exception& e) {
    say(e.what());
    return kExitCheckFailed;
  }
}

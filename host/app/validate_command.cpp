// `clothsim validate SCENE --frames N [--tolerance METRES]`: every GPU pass against its CPU
// twin from an identical state, then a lock-step run GPU vs CPU(float), with CPU(float) vs
// CPU(double) alongside as the float32 noise floor (docs/design.md §6).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gpu_simulator.hpp"
#include "pass_check.hpp"

namespace clothsim {
namespace {

struct Opts {
  SceneOptions scene;
  int frames = 100;
  double tolerance = -1;       // < 0: the noise floor
  double pass_tolerance = -1;  // < 0: exact on llvmpipe, 1e-5 m elsewhere
  int report_every = 10;
  int warmup = 20;
};

int run_validate(const Opts& o) {
  const Scene scene = o.scene.load();
  const ClothModel model = build_cloth(scene);
  auto context = require_headless_context();
  GpuSimulator gpu(scene, model, find_project_root() / "compute");
  fmt::print("{}: {}, {} substeps/frame, {}\n", scene.source, describe_cloth(model),
             scene.simulation.simulation_steps, gl::gl_renderer_string());

  // llvmpipe rounds exactly like the reference (no FMA, IEEE sqrt and division), so there
  // any difference at all is a bug; real GPUs get the float32 noise floor (docs/design.md §6).
  const bool exact = gl::gl_renderer_is_llvmpipe();
  const double pass_tolerance = o.pass_tolerance >= 0 ? o.pass_tolerance : (exact ? 0.0 : 1e-5);
  const std::string run_rule = o.tolerance >= 0 ? fmt::format("{:g} m", o.tolerance)
                               : exact ? std::string("0 (llvmpipe must match the reference bit for bit)")
                                       : std::string("twice the float32 noise floor (CPU float-double), min 1e-5 m");

  // 1. Each pass alone, from the state the CPU reaches after a warm-up (so there are
  //    velocities, stretched springs and contacts to get wrong).
  bool ok = true;
  fmt::print("per-pass check from an identical state after {} frames (tolerance {:g} m):\n", o.warmup,
             pass_tolerance);
  for (const PassError& e : check_passes(scene, model, gpu, o.warmup)) {
    const bool pass_ok = e.max_error <= pass_tolerance;
    ok = ok && pass_ok;
    if (e.integers)
      fmt::print("  {:<40} {}  {}\n", e.pass, e.differing ? fmt::format("{} elements differ", e.differing) : "equal",
                 pass_ok ? "ok" : "FAILED");
    else
      fmt::print("  {:<40} max {:.3e} m{}  {}\n", e.pass, e.max_error, e.bitwise ? " (bitwise equal)" : "",
                 pass_ok ? "ok" : "FAILED");
  }

  // 2. The whole run in lock step, on a fresh GPU state.
  gpu.upload(initial_state<float>(model));
  gpu.set_time(0);  // the pass checks left it at the warm-up's end
  CpuBackend<float> f32(scene, model);
  CpuBackend<double> f64(scene, model);
  State<float> g;
  double worst = 0, floor = 0;
  bool bitwise = true, run_ok = true;
  fmt::print("lock-step run, {} frames:\n  {:>6}  {:>12}  {:>12}  {:>18}\n", o.frames, "frame", "gpu-cpu max",
             "gpu-cpu rms", "cpu float-double");
  Progress progress("frame", o.frames);
  for (int f = 1; f <= o.frames; ++f) {
    gpu.step_frame();
    f32.step_frame();
    f64.step_frame();
    gpu.download(g);
    const Deviation d = deviation(g.pos, f32.state().pos);
    const Deviation n = deviation(f32.state().pos, f64.state().pos);
    worst = std::max(worst, d.max);
    floor = std::max(floor, n.max);
    bitwise = bitwise && d.bitwise;
    // Off llvmpipe the GPU's rounding (FMA, approximate sqrt) is float noise of its own, the
    // same size as the reference's float-vs-double noise and independent of it: twice that
    // floor, and never below 1e-5 m, the size of a few ULPs carried by the velocity for a while.
    const double limit = o.tolerance >= 0 ? o.tolerance : exact ? 0.0 : std::max(2 * floor, 1e-5);
    const bool frame_ok = std::isfinite(d.max) && d.max <= limit;
    if (!frame_ok && run_ok) fmt::print(stderr, "\nframe {}: GPU deviates {:.3e} m > tolerance {:.3e} m\n", f, d.max, limit);
    run_ok = run_ok && frame_ok;
    if (f % o.report_every == 0 || f == o.frames || !frame_ok) {
      progress.finish();
      fmt::print("  {:>6}  {:>12.3e}  {:>12.3e}  {:>18.3e}\n", f, d.max, d.rms, n.max);
    }
    progress.update(f);
  }
  progress.finish();
  fmt::print("max GPU-CPU(float) deviation {:.3e} m{}; float32 noise floor (CPU float-double) {:.3e} m; "
             "tolerance {}\n",
             worst, bitwise ? " (bitwise identical on every frame)" : "", floor, run_rule);
  ok = ok && run_ok;
  fmt::print("{}\n", ok ? "validation passed" : "validation FAILED");
  return ok ? kExitOk : kExitCheckFailed;
}

}  // namespace

void add_validate_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("validate", "check the GPU passes and a whole GPU run against the CPU reference");
  o->scene.add_to(*cmd, true);
  cmd->add_option("--frames", o->frames, "frames to run in lock step")->check(positive_number())->capture_default_str();
  cmd->add_option("--tolerance", o->tolerance,
                  "max GPU-CPU distance in metres over the run (default: 0 on llvmpipe, which rounds like "
                  "the reference; elsewhere twice the float32 noise floor, CPU float vs double, at least 1e-5 m)")
      ->check(non_negative_number());
  cmd->add_option("--pass-tolerance", o->pass_tolerance, "max error of each pass alone, metres (default: 0 on llvmpipe, 1e-5 elsewhere)")
      ->check(non_negative_number());
  cmd->add_option("--report-every", o->report_every, "print every K frames")->check(positive_number())->capture_default_str();
  cmd->add_option("--warmup", o->warmup, "CPU frames before the per-pass check")->check(non_negative_number())->capture_default_str();
  cmd->callback([o, &run] { run = [o] { return run_validate(*o); }; });
}

}  // namespace clothsim

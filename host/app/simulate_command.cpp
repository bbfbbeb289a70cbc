// `clothsim simulate SCENE --frames N [--backend gpu|cpu] [--export FILE.obj] [--stats]`
#include <chrono>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"

namespace clothsim {
namespace {

void print_stats(const Scene& scene, const ClothStats& st, int frames, double wall) {
  const int substeps = frames * scene.simulation.simulation_steps;
  fmt::print("frames            {}\n", frames);
  fmt::print("substeps          {}\n", substeps);
  fmt::print("wall time         {:.3f} s ({:.2f} ms/frame)\n", wall, frames ? 1e3 * wall / frames : 0.0);
  fmt::print("max stretch       {:.4f} x rest length\n", st.max_stretch_ratio);
  fmt::print("kinetic energy    {:.6g} J (max speed {:.4g} m/s)\n", st.kinetic, st.max_speed);
  for (size_t k = 0; k < st.sphere_clearance.size(); ++k)
    fmt::print("sphere[{}] clearance {:.6f} m\n", k, st.sphere_clearance[k]);
  for (size_t k = 0; k < st.plane_clearance.size(); ++k)
    fmt::print("plane[{}] clearance  {:.6f} m\n", k, st.plane_clearance[k]);
  fmt::print("finite            {}\n", st.finite ? "yes" : "NO (a value became NaN/Inf)");
}

}  // namespace

void add_simulate_command(CLI::App& app, std::function<int()>& run) {
  struct Opts {
    SceneOptions scene;
    int frames = 90;
    std::string backend = "gpu";
    std::string export_path;
    bool stats = false;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("simulate", "run a scene headless and report or export the result");
  o->scene.add_to(*cmd, true);
  cmd->add_option("--frames", o->frames, "frames to simulate")->check(CLI::NonNegativeNumber);
  cmd->add_option("--backend", o->backend, "gpu (compute shaders) or cpu (the reference)")
      ->check(CLI::IsMember({"gpu", "cpu"}))
      ->capture_default_str();
  cmd->add_option("--export", o->export_path, "write the final cloth as Wavefront OBJ");
  cmd->add_flag("--stats", o->stats, "print frames, timing, stretch, energy, clearances");
  cmd->callback([o, &run] {
    run = [o]() -> int {
      const Scene scene = o->scene.load();
      const ClothModel model = build_cloth(scene.cloth);
      std::unique_ptr<Backend> backend = make_backend(parse_backend(o->backend), scene, model);
      fmt::print("{}: {}x{} cloth, {} substeps/frame, backend {}\n", scene.source, model.nw, model.nh,
                 scene.simulation.simulation_steps, backend->name());
      auto export_obj = [&](const ClothSnapshot& snap, const std::string& what) {
        if (o->export_path.empty()) return;
        try {
          write_obj(o->export_path, model, snap);
        } catch (const std::runtime_error& e) {
          throw ExitError(kExitBadInput, fmt::format("--export {}", e.what()));
        }
        fmt::print("wrote {}{}\n", o->export_path, what);
      };
      Progress progress("frame", o->frames);
      // A diverged run stops with the message; --export still writes a finite cloth: the
      // newest frame that passed the check.
      auto stop_if_diverged = [&](const std::vector<FrameCheck>& checks) {
        for (const FrameCheck& check : checks) {
          const auto message = divergence_message(scene, model, check);
          if (!message) continue;
          progress.finish();
          if (!o->export_path.empty()) {
            int kept = 0;
            const ClothSnapshot good = backend->last_good(&kept);
            export_obj(good, fmt::format(" (frame {}, the last one that passed the divergence check)", kept));
          }
          throw ExitError(kExitCheckFailed, *message);
        }
      };
      const auto start = std::chrono::steady_clock::now();
      for (int f = 1; f <= o->frames; ++f) {
        backend->step_frame();
        // The divergence check: on the GPU a reduction whose 32-byte result arrives at most one
        // frame late, so the loop never waits for the frame it has just queued.
        stop_if_diverged(backend->take_checks(false));
        progress.update(f);
      }
      stop_if_diverged(backend->take_checks(true));
      progress.finish();
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const ClothSnapshot snap = backend->snapshot();
      if (o->stats) print_stats(scene, measure(scene, model, snap), o->frames, wall);
      export_obj(snap, "");
      return kExitOk;
    };
  });
}

}  // namespace clothsim

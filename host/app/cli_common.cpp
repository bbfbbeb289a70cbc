#include "cli_common.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include "checkpoint.hpp"
#include "mesh_collider.hpp"
#include "output_plan.hpp"

namespace clothsim {

void SceneOptions::add_to(CLI::App& cmd, bool positional_required) {
  auto* opt = cmd.add_option("scene", path, "scene JSON file (classic CS184 format or extended)");
  if (positional_required) opt->required();
  cmd.add_option("--set", sets, "override a scene value, e.g. --set cloth.ks=500 (repeatable; keys: docs/parameters.md)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  add_no_cache_flag(cmd);
}

void add_no_cache_flag(CLI::App& cmd) {
  cmd.add_flag_callback("--no-cache", disable_field_cache,
                        "neither read nor keep mesh colliders' fields in the cache folder ($XDG_CACHE_HOME/clothsim)");
}

Scene SceneOptions::load() const { return path.empty() ? default_scene(sets) : load_scene(path, sets); }

BackendKind parse_backend(const std::string& name) {
  if (name == "cpu") return BackendKind::Cpu;
  if (name == "gpu") return BackendKind::Gpu;
  throw ExitError(kExitBadInput, fmt::format("--backend: expected gpu or cpu, got '{}'", name));
}

void check_outputs(const OutputPlan& plan) {
  try {
    plan.check();
  } catch (const OutputError& e) {
    throw ExitError(kExitBadInput, e.what());
  }
}

// Reads and checks --load-state, then hands it to the backend; every failure is exit 2.
int64_t load_state(const std::string& path, const Scene& scene, const ClothModel& model, Backend& backend) {
  try {
    const Checkpoint c = read_checkpoint(path);
    check_fits(c, path, scene, model, backend.scalar_bytes(), backend.name());
    backend.load_state(c.state);
    fmt::print("loaded {}: frame {} ({:.4g} s simulated), saved by backend {} from {}\n", path, c.state.frame,
               c.state.time, c.backend, c.scene);
    // The displacements are per substep: another substep length rescales them (the cloth keeps
    // its velocity); a version-1 file did not record its length, so it is taken as this one.
    if (c.state.dt == 0)
      fmt::print("  (a version-1 state, which does not record its substep length: taken as this scene's {:.6g} s)\n",
                 scene.dt());
    else if (c.state.dt != scene.dt())
      fmt::print("  saved with substeps of {:.6g} s, this scene's are {:.6g} s: displacements scaled by {:.6g}\n",
                 c.state.dt, scene.dt(), scene.dt() / c.state.dt);
    return c.state.frame;
  } catch (const CheckpointError& e) {
    throw ExitError(kExitBadInput, fmt::format("--load-state {}", e.what()));
  }
}

Progress::Progress(std::string label, int total)
    : label_(std::move(label)), total_(total), tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(int done) {
  if (!tty_) return;
  auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  double secs = std::chrono::duration<double>(now - start_).count();
  double rate = secs > 0 ? done / secs : 0;
  double eta = rate > 0 ? (total_ - done) / rate : 0;
  fmt::print(stderr, "\r{} {}/{}  {:.1f} frames/s  ETA {:.0f} s   ", label_, done, total_, rate, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (tty_) fmt::print(stderr, "\r\033[K");
}

}  // namespace clothsim

#include "bench_runner.hpp"

#include <chrono>
#include <functional>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "gpu_simulator.hpp"

namespace clothsim {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

constexpr int kWarmupFrames = 2;

// Times each pass of one frame separately; `finish` waits for the work (glFinish on the GPU).
template <class Passes>
std::map<std::string, double> time_passes(int substeps, const Passes& passes, const std::function<void()>& finish) {
  std::map<std::string, double> ms;
  for (int k = 0; k < substeps; ++k)
    for (auto& [name, run] : passes.step) {
      finish();
      const auto t = Clock::now();
      run();
      finish();
      ms[name] += ms_since(t);
    }
  finish();
  const auto t = Clock::now();
  passes.normals();
  finish();
  ms["compute_normals"] = ms_since(t);
  return ms;
}

struct PassList {
  std::vector<std::pair<std::string, std::function<void()>>> step;
  std::function<void()> normals;
};

}  // namespace

Scene bench_scene(int n, bool self_collision) {
  const double spacing = 1.0 / (n - 1), classic_spacing = 1.0 / 49;
  const double ks = 5000.0 * (spacing / classic_spacing) * (spacing / classic_spacing);
  const std::string json = fmt::format(
      R"({{"cloth": {{"width": 1, "height": 1, "num_width_points": {0}, "num_height_points": {0},
           "thickness": {1}, "orientation": 0, "ks": {2}, "pinned": [[0,0],[{3},0],[0,{3}],[{3},{3}]]}},
         "sphere": {{"origin": [0.5, 0.55, 0.5], "radius": 0.25, "friction": 0.3}},
         "plane": {{"point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5}},
         "simulation": {{"self_collision": {4}}}}})",
      n, 0.0095 / classic_spacing * spacing, ks, n - 1, self_collision ? "true" : "false");
  return parse_scene(json, fmt::format("<bench {}x{}>", n, n));
}

BenchRunner::BenchRunner(const std::string& root, int frames)
    : context_(require_headless_context()), renderer_(gl::gl_renderer_string()),
      compute_dir_((find_project_root(root) / "compute").string()), frames_(frames) {}

BenchRunner::~BenchRunner() = default;

BenchResult BenchRunner::run_gpu(const Scene& scene) {
  const ClothModel model = build_cloth(scene.cloth);
  GpuSimulator sim(scene, model, compute_dir_);
  for (int f = 0; f < kWarmupFrames; ++f) sim.step_frame();
  glFinish();
  const GpuCounters before = sim.counters();
  const auto t = Clock::now();
  for (int f = 0; f < frames_; ++f) sim.step_frame();
  glFinish();
  BenchResult r;
  r.ms_per_frame = ms_since(t) / frames_;
  const GpuCounters after = sim.counters();
  r.dispatches_per_frame = double(after.dispatches - before.dispatches) / frames_;
  r.barriers_per_frame = double(after.barriers - before.barriers) / frames_;
  r.gpu_memory_bytes = sim.memory_bytes();
  // The passes of GpuSimulator::step, the hash stages one by one ("collide_self" is the
  // response over the finished hash); collide_objects is fused into advance or collide_self.
  const bool sc = scene.simulation.self_collision;
  const bool colliders = !sim.constants().spheres.empty() || !sim.constants().planes.empty();
  PassList passes{{{"advance", [&] { sim.advance(colliders && !sc); }},
                   {"count_cells", [&] { if (sc) sim.count_cells(); }},
                   {"scan_cells", [&] { if (sc) sim.scan_cells(); }},
                   {"fill_cells", [&] { if (sc) sim.fill_cells(); }},
                   {"sort_cells", [&] { if (sc) sim.sort_cells(); }},
                   {"collide_self", [&] { if (sc) sim.resolve_self_contacts(colliders); }},
                   {"solve_length_constraints", [&] { sim.solve_length_constraints(); }}},
                  [&] { sim.compute_normals(); }};
  // llvmpipe has no GPU timer queries, so every pass is timed with glFinish around it, in
  // a separate frame (the glFinish calls would distort the throughput run above).
  r.pass_ms = time_passes(scene.simulation.simulation_steps, passes, [] { glFinish(); });
  // The divergence guard, once per frame: its reduction and the copy of a passing frame.
  glFinish();
  const auto guard_start = Clock::now();
  sim.divergence().check(sim.positions());
  glFinish();
  r.pass_ms["check_divergence"] = ms_since(guard_start);
  r.pass_timing = "glFinish + steady clock around each pass, separate frame";
  r.particles = model.count();
  r.substeps_per_frame = scene.simulation.simulation_steps;
  r.particle_substeps_per_s = double(r.particles) * r.substeps_per_frame / (r.ms_per_frame * 1e-3);
  return r;
}

BenchResult BenchRunner::run_cpu(const Scene& scene) {
  const ClothModel model = build_cloth(scene.cloth);
  CpuBackend<float> cpu(scene, model);
  for (int f = 0; f < kWarmupFrames; ++f) cpu.step_frame();
  const auto t = Clock::now();
  for (int f = 0; f < frames_; ++f) cpu.step_frame();
  BenchResult r;
  r.ms_per_frame = ms_since(t) / frames_;
  const auto& c = cpu.constants();
  auto& s = cpu.state();
  PassList passes{{{"advance", [&] { advance(model, c, s); }},
                   {"collide_self", [&] { if (c.self_collision) collide_self(c, s); }},
                   {"collide_objects", [&] { collide_objects(c, s); }},
                   {"solve_length_constraints", [&] { solve_length_constraints(model, c, s); }}},
                  [&] { compute_normals(model, s); }};
  r.pass_ms = time_passes(scene.simulation.simulation_steps, passes, [] {});
  const auto guard_start = Clock::now();
  KeptFrame<float> kept;
  keep_last_good(check_divergence(s.pos), divergence_limits(scene, model), 1, s.pos, kept);
  r.pass_ms["check_divergence"] = ms_since(guard_start);
  r.pass_timing = "steady clock around each pass (CPU reference, float)";
  r.particles = model.count();
  r.substeps_per_frame = scene.simulation.simulation_steps;
  r.particle_substeps_per_s = double(r.particles) * r.substeps_per_frame / (r.ms_per_frame * 1e-3);
  cpu_rate_[scene.simulation.self_collision] = r.particle_substeps_per_s;
  return r;
}

double BenchRunner::estimate_cpu_seconds(const Scene& scene) const {
  auto it = cpu_rate_.find(scene.simulation.self_collision);
  const double rate = it != cpu_rate_.end() ? it->second : 1e6;  // a slow CPU's rate before any measurement
  return double(scene.particle_count()) * scene.simulation.simulation_steps * (frames_ + kWarmupFrames + 1) / rate;
}

nlohmann::json to_json(const BenchResult& r, const std::string& backend, int size, bool sc) {
  return {{"backend", backend},
          {"size", size},
          {"particles", r.particles},
          {"self_collision", sc},
          {"substeps_per_frame", r.substeps_per_frame},
          {"ms_per_frame", r.ms_per_frame},
          {"particle_substeps_per_s", r.particle_substeps_per_s},
          {"pass_ms", r.pass_ms},
          {"pass_timing", r.pass_timing},
          {"dispatches_per_frame", r.dispatches_per_frame},
          {"barriers_per_frame", r.barriers_per_frame},
          {"gpu_memory_bytes", r.gpu_memory_bytes}};
}

}  // namespace clothsim

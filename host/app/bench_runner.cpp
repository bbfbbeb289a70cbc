#include "bench_runner.hpp"

#include <chrono>
#include <stdexcept>
#include <functional>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "gpu_simulator.hpp"

namespace clothsim {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

constexpr int kWarmupFrames = 2;

using Pass = std::pair<std::string, std::function<void()>>;

// The passes of one frame: `step` once per substep, then `frame` once (normals, guard).
struct PassList {
  std::vector<Pass> step, frame;
  template <class F> void for_each(int substeps, F&& f) const {
    for (int k = 0; k < substeps; ++k)
      for (const Pass& p : step) f(p);
    for (const Pass& p : frame) f(p);
  }
};

// Times each pass of one frame separately; `finish` waits for the work (glFinish on the GPU).
std::map<std::string, double> time_passes(int substeps, const PassList& passes, const std::function<void()>& finish) {
  std::map<std::string, double> ms;
  passes.for_each(substeps, [&](const Pass& p) {
    finish();
    const auto t = Clock::now();
    p.second();
    finish();
    ms[p.first] += ms_since(t);
  });
  return ms;
}

// The GPU time of each pass of one frame from GL_TIME_ELAPSED queries (no stall between
// passes); empty when the driver has no real GPU timer: llvmpipe's queries read 0 or a few
// nanoseconds, so a sum under 5 % of the measured frame time means "no timer".
std::map<std::string, double> time_passes_with_queries(int substeps, const PassList& passes, double frame_ms) {
  std::vector<std::pair<std::string, GLuint>> issued;
  passes.for_each(substeps, [&](const Pass& p) {
    GLuint id = 0;
    glGenQueries(1, &id);
    glBeginQuery(GL_TIME_ELAPSED, id);
    p.second();
    glEndQuery(GL_TIME_ELAPSED);
    issued.emplace_back(p.first, id);
  });
  std::map<std::string, double> ms;
  GLuint64 total = 0;
  for (auto& [name, id] : issued) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(id, GL_QUERY_RESULT, &ns);
    glDeleteQueries(1, &id);
    ms[name] += double(ns) * 1e-6;
    total += ns;
  }
  if (double(total) * 1e-6 < 0.05 * frame_ms) ms.clear();
  return ms;
}

}  // namespace

const char* solver_name(Solver solver) {
  return solver == Solver::Fabric ? "fabric" : "classic";
}

Solver solver_of(const std::string& name) {
  for (Solver s : kBenchSolvers)
    if (name == solver_name(s)) return s;
  throw std::invalid_argument("unknown solver " + name);  // --solver's check lets none through
}

std::vector<std::string> solver_names() {
  std::vector<std::string> names;
  for (Solver s : kBenchSolvers) names.push_back(solver_name(s));
  return names;
}

Scene bench_scene(int n, bool self_collision, Solver solver) {
  const double spacing = 1.0 / (n - 1), classic_spacing = 1.0 / 49;
  // Both position-based solvers take fabric values; the classic one needs softer, heavier cloth.
  const bool fabric = solver != Solver::Classic;
  const double ks = fabric ? 5000.0 : 5000.0 * (spacing / classic_spacing) * (spacing / classic_spacing);
  const std::string json = fmt::format(
      R"({{"cloth": {{"width": 1, "height": 1, "num_width_points": {0}, "num_height_points": {0},
           "thickness": {1}, "orientation": 0, "ks": {2}, "density": {5}, "pinned": [[0,0],[{3},0],[0,{3}],[{3},{3}]]}},
         "sphere": {{"origin": [0.5, 0.55, 0.5], "radius": 0.25, "friction": 0.3}},
         "plane": {{"point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5}},
         "simulation": {{"self_collision": {4}, "solver": "{6}"}}}})",
      n, 0.0095 / classic_spacing * spacing, ks, n - 1, self_collision ? "true" : "false", fabric ? 0.15 : 150.0,
      solver_name(solver));
  return parse_scene(json, fmt::format("<bench {}x{}{}>", n, n, fabric ? std::string(" ") + solver_name(solver) : ""));
}

BenchRunner::BenchRunner(const std::string& root, int frames)
    : context_(require_headless_context()), renderer_(gl::gl_renderer_string()),
      compute_dir_((find_project_root(root) / "compute").string()), frames_(frames) {}

BenchRunner::~BenchRunner() = default;

BenchResult BenchRunner::run_gpu(const Scene& scene) {
  const ClothModel model = build_cloth(scene);
  GpuSimulator sim(scene, model, compute_dir_);
  for (int f = 0; f < kWarmupFrames; ++f) sim.step_frame();
  glFinish();
  const GpuCounters before = sim.passes().counters();
  const auto t = Clock::now();
  for (int f = 0; f < frames_; ++f) sim.step_frame();
  glFinish();
  BenchResult r;
  r.ms_per_frame = ms_since(t) / frames_;
  const GpuCounters after = sim.passes().counters();
  r.dispatches_per_frame = double(after.dispatches - before.dispatches) / frames_;
  r.barriers_per_frame = double(after.barriers - before.barriers) / frames_;
  r.gpu_memory_bytes = sim.memory_bytes();
  // The pass table's stage rows (pass_table.hpp): the entries of GpuSimulator::step, collide_self
  // as its five stages (timed as nothing without self-collision), collide_objects fused into
  // the first pass or resolve_self_contacts, the V-cycle as cycle_levels, the limit as
  // enforce_stretch_limit; then the frame's (compute_normals) and the divergence guard.
  PassList passes;
  const uint16_t f = sim.passes().features();
  for (const PassRow& row : kPasses) {
    if (!row.stage) continue;
    const char* name = stage_name(row);
    const PassId id = row.id;
    if (runs(row, f | kSelf)) passes.step.push_back({name, [&sim, id] { sim.run_stage(id); }});
    else if (runs(row, f | kPerFrame) && (row.need & kPerFrame)) passes.frame.push_back({name, [&sim, id] { sim.run(id); }});
  }
  // The divergence guard: its reduction and the copy of a passing frame.
  passes.frame.push_back({"check_divergence", [&] { sim.passes().divergence().check(sim.state().positions()); }});
  // Per-pass times come from a separate frame (stalls or queries would distort the run above):
  // GPU timer queries where the driver has them, else (llvmpipe) glFinish around each pass.
  const int substeps = scene.simulation.simulation_steps;
  r.pass_ms = time_passes_with_queries(substeps, passes, r.ms_per_frame);
  r.pass_timing = "GL_TIME_ELAPSED query around each pass, separate frame";
  if (r.pass_ms.empty()) {
    r.pass_ms = time_passes(substeps, passes, [] { glFinish(); });
    r.pass_timing = "glFinish + steady clock around each pass, separate frame (no GPU timer)";
  }
  r.particles = model.count();
  r.springs = int(model.springs.size());
  r.colours = model.colours();
  r.substeps_per_frame = scene.simulation.simulation_steps;
  r.particle_substeps_per_s = double(r.particles) * r.substeps_per_frame / (r.ms_per_frame * 1e-3);
  return r;
}

BenchResult BenchRunner::run_cpu(const Scene& scene) {
  const ClothModel model = build_cloth(scene);
  CpuBackend<float> cpu(scene, model);
  for (int f = 0; f < kWarmupFrames; ++f) cpu.step_frame();
  const auto t = Clock::now();
  for (int f = 0; f < frames_; ++f) cpu.step_frame();
  BenchResult r;
  r.ms_per_frame = ms_since(t) / frames_;
  const auto& c = cpu.constants();
  auto& s = cpu.state();
  std::vector<Pass> solve;  // the solver's passes, each timed on its own
  if (c.multigrid)
    solve = {{"compute_residuals", [&] { compute_residuals(model, c, s); }},
             {"cycle_levels", [&] { cycle_levels(c, s); }},
             {"prolong_to_cloth", [&] { prolong_to_cloth(model, c, s); }},
             {"relax_vertices", [&] {
                for (int k = 0; k < c.hierarchy->fine_colours(); ++k) relax_vertices(model, c, k, s);
              }}};
  else solve = {{"solve_length_constraints", [&] { solve_length_constraints(model, c, s); }}};
  if (c.stretch_passes_max > 0) solve.push_back({"enforce_stretch_limit", [&] { enforce_stretch_limit(model, c, s); }});
  PassList passes{{{c.multigrid ? "predict" : "advance", [&] { c.multigrid ? predict(model, c, s) : advance(model, c, s); }},
                   {"collide_self", [&] { if (c.self_collision) collide_self(c, s); }},
                   {"collide_objects", [&] { collide_objects(c, s); }}},
                  {{"compute_normals", [&] { compute_normals(model, s); }},
                   {"check_divergence", [&] {
                      KeptFrame<float> kept;
                      keep_last_good(check_divergence(s.pos), divergence_limits(scene, model), 1, s.pos, kept);
                    }}}};
  passes.step.insert(passes.step.end(), solve.begin(), solve.end());
  r.pass_ms = time_passes(scene.simulation.simulation_steps, passes, [] {});
  r.pass_timing = "steady clock around each pass (CPU reference, float)";
  r.particles = model.count();
  r.springs = int(model.springs.size());
  r.colours = model.colours();
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

nlohmann::json to_json(const BenchResult& r, const std::string& backend, const std::string& solver, int size,
                       bool sc) {
  return {{"backend", backend},
          {"solver", solver},
          {"size", size},
          {"particles", r.particles},
          {"springs", r.springs},
          {"colours", r.colours},
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

// One bench configuration at a time: the scene, the timed frame loop, per-pass timings.
#pragma once

#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "context.hpp"
#include "scene/scene.hpp"

namespace clothsim {

struct BenchResult {
  int particles = 0, substeps_per_frame = 0;
  int springs = 0, colours = 0;  // of the cloth model: one constraint dispatch per colour
  double ms_per_frame = 0, particle_substeps_per_s = 0;
  std::map<std::string, double> pass_ms;  // per frame
  std::string pass_timing;                // how pass_ms was measured
  double dispatches_per_frame = 0, barriers_per_frame = 0;
  size_t gpu_memory_bytes = 0;
};

// A square n x n cloth of 1 m, corners pinned, over a sphere and a plane. Thickness follows
// the spacing (the classic 0.0095 m at 0.0204 m spacing). classic: ks keeps the classic
// sqrt(ks / mass) so every size is as stable as the classic scene at 30 substeps; fabric:
// physical values at every size (fabric density 0.15 kg/m^2, ks 5000 N/m).
Scene bench_scene(int n, bool self_collision, Solver solver = Solver::Classic);
const char* solver_name(Solver solver);  // as the scene key spells it
Solver solver_of(const std::string& name);  // the inverse of solver_name
// Every solver bench runs, classic first (the others are timed against it).
inline constexpr Solver kBenchSolvers[] = {Solver::Classic, Solver::Fabric};
std::vector<std::string> solver_names();  // of kBenchSolvers, in order

class BenchRunner {
 public:
  BenchRunner(const std::string& root, int frames);
  ~BenchRunner();
  const std::string& renderer() const { return renderer_; }
  BenchResult run_gpu(const Scene& scene);
  BenchResult run_cpu(const Scene& scene);
  // From the CPU throughput measured so far (or a conservative guess before the first run).
  double estimate_cpu_seconds(const Scene& scene) const;

 private:
  std::unique_ptr<gl::GlContext> context_;
  std::string renderer_, compute_dir_;
  int frames_;
  std::map<bool, double> cpu_rate_;  // particle-substeps/s by self-collision
};

nlohmann::json to_json(const BenchResult& r, const std::string& backend, const std::string& solver, int size,
                       bool self_collision);

}  // namespace clothsim

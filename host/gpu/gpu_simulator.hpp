// The model of DESIGN.md §1 as compute passes over shader-storage buffers. The passes have
// the names of the CPU reference functions they mirror; step() is the same pass list.
// Positions stay on the GPU: the only read-backs are download() and snapshot(), on request.
#pragma once

#include <filesystem>
#include <memory>

#include "backend.hpp"
#include "context.hpp"
#include "gpu_divergence.hpp"
#include "objects.hpp"
#include "prefix_scan.hpp"
#include "program.hpp"
#include "../../compute/layout.glsl"

namespace clothsim {

class GpuSimulator {
 public:
  // Needs a current GL 4.3 context. `compute_dir` holds the .comp files.
  GpuSimulator(const Scene& scene, const ClothModel& model, const std::filesystem::path& compute_dir);

  // The passes, one dispatch each (the length constraint: one per colour and iteration).
  void accumulate_forces();
  void integrate();
  void collide_self();  // the four hash stages below, then the Jacobi response
  void collide_objects();
  void solve_length_constraint_colour(int colour);
  void solve_length_constraints();
  void compute_normals();

  // The stages of collide_self, named like their shaders and CPU twins.
  void count_cells();
  void scan_cells();
  void fill_cells();
  void sort_cells();
  void download_hash(SpatialHash& hash);  // count (cursors after fill), start, entries
  // The scanner, for tests of arbitrary lengths (up to the hash table size).
  PrefixScan& prefix_scan() { return scan_; }

  void step();        // one substep, the pass list of §1
  void step_frame();  // simulation_steps substeps, then normals, then the divergence guard's check
  GpuDivergenceGuard& divergence() { return guard_; }

  // Explicit transfers for export, validation and tests.
  void upload(const State<float>& state);  // pos, prev, and force when present
  void download(State<float>& state);  // pos, prev, force, normal

  // Live edits from the viewer. Parameters that keep the grid (stiffness, damping, density,
  // gravity, steps, thickness, ...) apply without a restart; a changed mass rescales every
  // inverse mass in place. The grid itself (size, points, orientation, pins) needs a new simulator.
  void set_parameters(const Scene& scene);
  // Holds particle i at `position` (pos and prev, inverse mass 0) until release_particle.
  void hold_particle(int i, const glm::vec3& position);
  void release_particle(int i);  // back to its own inverse mass (0 if it is pinned)
  void reset();                  // back to the initial state

  // The buffers the renderer reads in place.
  const gl::Buffer& positions() const { return positions_; }
  const gl::Buffer& normals() const { return normals_; }
  int dispatches_per_substep() const;
  GpuCounters counters() const;   // dispatches and barriers issued so far
  size_t memory_bytes() const;    // GPU buffer memory this simulator owns
  const Constants<float>& constants() const { return constants_; }

 private:
  void bind_all() const;
  void upload_colliders();  // from constants_
  void barrier(GLbitfield bits);  // glMemoryBarrier, counted
  void dispatch(gl::Program& program);

  const ClothModel& model_;
  const std::filesystem::path dir_;
  Constants<float> constants_;
  layout::StepParams params_{};
  float inverse_mass_;
  GpuCounters counters_;  // of a free particle, for the current density
  GLuint groups_ = 0;
  gl::Buffer positions_{"positions"}, previous_{"previous"}, forces_{"forces"}, normals_{"normals"};
  gl::Buffer rest_{"rest lengths"}, spheres_{"spheres"}, planes_{"planes"}, step_params_{"step params"};
  gl::Buffer positions_out_{"positions out"}, cell_count_{"cell count"}, cell_start_{"cell start"};
  gl::Buffer cell_entries_{"cell entries"};
  uint32_t table_size_ = 0;
  gl::Program accumulate_forces_, integrate_, collide_objects_, solve_length_constraints_, compute_normals_;
  gl::Program count_cells_, fill_cells_, sort_cells_, collide_self_;
  PrefixScan scan_;
  GpuDivergenceGuard guard_;
};

// The parameter block of a substep, from the same Constants<float> the reference uses.
layout::StepParams make_step_params(const Constants<float>& c, const ClothModel& m);

// The GPU simulator as a Backend: owns the headless context it runs in.
class GpuBackend final : public Backend {
 public:
  GpuBackend(std::unique_ptr<gl::GlContext> context, const Scene& scene, const ClothModel& model,
             const std::filesystem::path& compute_dir);
  void step_frame() override { sim_->step_frame(); }
  ClothSnapshot snapshot() override;
  std::vector<FrameCheck> take_checks(bool all) override { return sim_->divergence().take(all); }
  ClothSnapshot last_good(int* frame) override {
    return snapshot_of_positions(model_, sim_->divergence().last_good(frame));
  }
  std::string name() const override;
  GpuSimulator& simulator() { return *sim_; }

 private:
  std::unique_ptr<gl::GlContext> context_;
  const ClothModel& model_;
  std::unique_ptr<GpuSimulator> sim_;
};

// Where the GLSL files are: $CLOTHSIM_ROOT, then the directory above the executable
// (build/ in a source tree), then the source tree the binary was built from.
std::filesystem::path find_project_root(const std::filesystem::path& hint = {});

}  // namespace clothsim

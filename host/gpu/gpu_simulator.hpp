// The model of docs/design.md §1 as compute passes over shader-storage buffers. The passes have
// the names of the CPU reference functions they mirror; step() is the same pass list.
// Positions stay on the GPU: the only read-backs are download() and snapshot(), on request.
// Composed of three parts that GpuSimulator owns: a GpuState (gpu_state.hpp: the buffers and
// views), the Constants (the model and its per-substep Control) and a GpuPasses (gpu_passes.hpp:
// the pass table's programs and run(PassId), on that state); GpuSimulator is the orchestrator:
// gpu_simulator.cpp (construction, the step), gpu_simulator_io.cpp (transfers), gpu_edits.cpp
// (live edits and the grab).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "backend.hpp"
#include "context.hpp"
#include "gpu_passes.hpp"

namespace clothsim {

class GpuSimulator {
 public:
  // Needs a current GL 4.3 context. `compute_dir` holds the .comp files.
  GpuSimulator(const Scene& scene, const ClothModel& model, const std::filesystem::path& compute_dir);
  ~GpuSimulator();

  void step();        // one substep, the pass list of §1; then time() is one substep later
  // One entry of the step (a pass table row marked `stage`) as step() runs it, collide_objects
  // fused where the step fuses it; nothing where the scene does not run it (bench's rows).
  void run_stage(PassId stage);
  // simulation_steps substeps, then normals, then the divergence guard's check. Throws
  // gl::GlError (gl::OutOfMemoryError for GL_OUT_OF_MEMORY) naming the GL error and the frame
  // when glGetError reports one, before the frame's passes (raised since the last frame by
  // another GL user) or after them (raised by a pass); debug builds also check after each pass.
  void step_frame();
  // Times every stage row, the substep's control upload, the normals and the divergence check of
  // the frames that follow into `profile` (null: no longer), a glFinish before and after each.
  void set_profile(PassProfile* profile) { passes_.profile_ = profile; }

  // Simulated seconds at the start of the next substep. set_time also sets the moving parts
  // (colliders, pins, gusts) for the substep starting at t, as set_substep_time does on the
  // CPU (a checkpoint's time, or a pass check's).
  double time() const { return time_; }
  void set_time(double t);

  // Explicit transfers for export, validation and tests.
  void upload(const State<float>& state);  // pos, disp, and force and wind when present
  void download(State<float>& state);  // pos, disp, force, normal, and wind with wind

  // Live edits from the viewer. Parameters that keep the grid (stiffness, damping, density,
  // gravity, steps, thickness, ...) apply without a restart; a changed mass rescales every
  // inverse mass in place, a changed substep length every displacement (rescale_displacement:
  // the cloth keeps its velocity). The grid itself (size, points, orientation, pins) needs a new simulator.
  void set_parameters(const Scene& scene);
  // Holds particle i at `position` (at rest: displacement 0, inverse mass 0) until release_particle.
  void hold_particle(int i, const glm::vec3& position);
  void release_particle(int i);  // back to its own inverse mass (0 if it is pinned)
  void reset();                  // back to the initial state
  size_t memory_bytes() const;    // GPU buffer memory this simulator owns

  // One pass, as GpuPasses::run (tests, pass checks, a checkpoint's normals).
  void run(PassId pass, PassArgs args = {}) { passes_.run(pass, args); }
  GpuState& state() { return state_; }
  const GpuState& state() const { return state_; }
  GpuPasses& passes() { return passes_; }
  const GpuPasses& passes() const { return passes_; }
  const Constants<float>& constants() const { return constants_; }

 private:
  std::vector<float> inverse_masses() const;  // of every particle for the current densities
  void apply_substep_time();  // the moving parts of constants_ for the substep at time_, uploaded

  GpuState state_;  // first: its constructor checks the GPU's limits before anything is made
  Constants<float> constants_;
  GpuPasses passes_;  // runs on state_ for constants_
  std::vector<double> masses_;  // kg, for the current densities (particle_masses)
  double dt_;  // the substep length the displacements are per
  double time_ = 0;  // simulated seconds at the start of the next substep
};

// The GPU simulator as a Backend: owns the headless context it runs in.
class GpuBackend final : public Backend {
 public:
  GpuBackend(std::unique_ptr<gl::GlContext> context, const Scene& scene, const ClothModel& model,
             const std::filesystem::path& compute_dir);
  void step_frame() override { sim_->step_frame(); }
  ClothSnapshot snapshot() override;
  std::vector<FrameCheck> take_checks(bool all) override { return sim_->passes().divergence().take(all); }
  ClothSnapshot last_good(int* frame) override {
    return snapshot_of_positions(model_, sim_->passes().divergence().last_good(frame));
  }
  std::string name() const override;
  SavedState save_state() override;
  void load_state(const SavedState& saved) override;
  int scalar_bytes() const override { return int(sizeof(float)); }
  double time() const override { return sim_->time(); }
  uint64_t stretch_settling_passes() const override { return sim_->state().stretch_settling_passes(); }
  void set_profile(PassProfile* profile) override { sim_->set_profile(profile); }
  GpuSimulator& simulator() { return *sim_; }
  const GpuSimulator& simulator() const { return *sim_; }

 private:
  std::unique_ptr<gl::GlContext> context_;
  const ClothModel& model_;
  std::unique_ptr<GpuSimulator> sim_;
};

// Where the GLSL files are: $CLOTHSIM_ROOT, then the directory above the executable
// (build/ in a source tree), then the source tree the binary was built from.
std::filesystem::path find_project_root(const std::filesystem::path& hint = {});

}  // namespace clothsim

// The passes (issue 42, item 3): every row of the pass table (pass_table.hpp) compiled, and run
// one at a time by run(PassId), each dispatch sized by its row's domain and followed by its
// row's barrier. Split: gpu_passes.cpp (loading, dispatch, the counts), gpu_step.cpp (run and
// the sweeps), gpu_multigrid.cpp, gpu_stretch_limit.cpp, gpu_contacts.cpp.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "gpu_divergence.hpp"
#include "gpu_state.hpp"
#include "pass_table.hpp"
#include "prefix_scan.hpp"
#include "program.hpp"
#include "shader_features.hpp"

namespace clothsim {

// Where run() applies a pass: a level or colour of its own (-1: every one, as the step runs it),
// `sweeps` sweeps over a level's colours (smooth_corrections), and whether collide_objects rides
// along (advance, predict, resolve_self_contacts: the fused passes of the step).
struct PassArgs {
  int level = -1, colour = -1, sweeps = 1;
  bool collide_objects = false;
};

// The items a dispatch over a range covers (u_first, u_count).
struct PassSpan {
  uint32_t first = 0, count = 0;
};

// Runs on a GpuState it does not own, for the constants it is given (both GpuSimulator's,
// which outlive it).
class GpuPasses {
 public:
  // Needs a current GL 4.3 context. `compute_dir` holds the .comp files.
  GpuPasses(GpuState& state, const Constants<float>& constants, const Scene& scene, const ClothModel& model,
            const std::filesystem::path& compute_dir);
  ~GpuPasses();

  // One pass of the table, named like its .comp file and its CPU twin (host/core/reference),
  // as step() runs it: solve_length_constraints every iteration of every enabled colour (or
  // `colour` alone), advance and predict with collide_objects over the contact list after them
  // where `collide_objects`, scan_cells the prefix scan, stretch_fixed_passes the whole
  // enforce_stretch_limit. accumulate_forces, integrate and collide_objects on their own are
  // only for the pass checks (pass_check.cpp).
  void run(PassId pass, PassArgs args = {});
  // The passes made of several rows.
  void collide_self(bool then_collide_objects = false);  // count, scan, fill and sort the cells, then the response
  void enforce_stretch_limit();  // fabric's stretch_passes, then the settling ones
  void cycle_levels();  // the V-cycle: every multigrid pass between compute_residuals and prolong_to_cloth
  void solve_multigrid();
  int dispatches_per_substep() const;  // from the table's counts (pass_table.cpp)
  int multigrid_dispatches() const;    // of one solve_multigrid
  GpuCounters counters() const;        // dispatches and barriers issued so far
  SubstepShape shape() const;          // the scene's features and what the table's counts need
  // The scene's features alone: which rows a substep runs. Cheap, unlike shape(), which also
  // walks the colours and levels for the counts; the step asks for it per stage.
  uint16_t features() const { return features_of(constants_, uses_contact_list()); }
  // The multigrid scratch (State::residual, coarse_rhs, coarse_corr), for the pass checks; the
  // offsets, which fabric carries between substeps, go with GpuSimulator::upload and download.
  void download_multigrid(State<float>& state);
  void upload_multigrid(const State<float>& state);
  PrefixScan& prefix_scan() { return scan_; }  // for tests of arbitrary lengths
  GpuDivergenceGuard& divergence() { return guard_; }
  const ShaderFeatures& shader_features() const { return features_; }  // what the passes are compiled for

  // Compiles every row built always for `features` (at construction, and when a live edit
  // changes them); the multigrid and settling rows wait for their first use.
  void load_passes(const ShaderFeatures& features);
  void ensure_multigrid();  // the multigrid rows and buffers (again after an edit rebuilt the hierarchy)
  std::string pass_list() const { return clothsim::pass_list(shape()); }

 private:
  friend class GpuSimulator;  // its step sets in_step_, in_frame_ and substep_

  void bind_for_pass() const { if (!in_step_) state_.bind_all(); }
  void load_rows(Build build);  // the rows of one Build
  // One dispatch of `pass`'s program sized by its row's domain over `span` (u_first, u_count),
  // then the row's barrier, with its listed_barrier where `listed`.
  void dispatch_row(PassId pass, PassSpan span = {}, bool listed = false, GLintptr indirect = 0);
  void dispatched(const gl::Program& program);  // counts a dispatch; debug builds check GL errors
  void barrier(GLbitfield bits);  // glMemoryBarrier, counted
  void first_pass(PassId pass, bool then_collide_objects);  // advance or predict
  void colour_pass(PassId pass, int colour);  // one colour of a constraint sweep
  // Runs f; with a profile (simulate --profile), timed as `name` between two glFinish calls.
  template <class F> void timed(std::string_view name, F&& f) {
    profiled(profile_, name, std::forward<F>(f), [] { glFinish(); });
  }
  void level_pass(PassId pass, const PassArgs& args);  // a multigrid pass over a level or colour
  // `passes` sweeps of solve_length_constraints' shader over every enabled colour, as `row`.
  void length_constraint_passes(int passes, PassId row = PassId::solve_length_constraints);
  void settling_passes(int fixed);  // enforce_stretch_limit's watched passes (gpu_stretch_limit.cpp)
  bool enabled_colour(int colour) const;  // has springs, of a type some cloth has on
  // The contact list (gpu_contacts.cpp): whether the step collides through it, the cleared list.
  bool uses_contact_list() const;
  void start_contact_list();

  GpuState& state_;
  const Constants<float>& constants_;
  const std::filesystem::path dir_;
  GpuCounters counters_;
  GLuint groups_ = 0;  // of a dispatch over every particle
  bool in_step_ = false;
  bool in_frame_ = false;  // within step_frame's substeps
  int substep_ = 0;        // of the frame, while in_frame_
  PassProfile* profile_ = nullptr;  // GpuSimulator::set_profile's, while simulate --profile times
  ShaderFeatures features_;  // what the programs were compiled for
  bool settling_loaded_ = false;
  std::array<gl::Program, kPassCount> programs_;  // by row; Build::shared and none rows have none
  // Per row, looked up once: u_first and u_count (range domains), its flag uniform.
  std::array<GLint, kPassCount> first_{}, count_{}, flag_{};
  PrefixScan scan_;
  GpuDivergenceGuard guard_;
};

}  // namespace clothsim

// The passes and the step: one dispatch per pass, each followed by a barrier that says who
// reads next. Bindings are made once per step (bind_all); a pass called on its own binds first.
#include "gpu_simulator.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "debug_output.hpp"

namespace clothsim {
namespace {

// Sets a flag for a scope, cleared however the scope ends (a GL error throws out of a frame).
struct ScopedFlag {
  explicit ScopedFlag(bool& flag) : flag_(flag) { flag_ = true; }
  ~ScopedFlag() { flag_ = false; }
  ScopedFlag(const ScopedFlag&) = delete;
  ScopedFlag& operator=(const ScopedFlag&) = delete;
  bool& flag_;
};

}  // namespace

void GpuSimulator::swap_positions() {
  std::swap(positions_, positions_out_);
  std::swap(positions_view_, positions_out_view_);
  // Only these two changed places; every other binding of the step holds.
  positions_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS);
  positions_out_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS_OUT);
  positions_view_.bind(TEXTURE_POSITIONS);
}

void GpuSimulator::dispatch(gl::Program& program) {
  bind_for_pass();
  program.dispatch(groups_);
  dispatched(program);
}

void GpuSimulator::dispatched([[maybe_unused]] const gl::Program& program) {
  ++counters_.dispatches;
#ifndef NDEBUG
  // Debug builds look after every pass, so a GL error names the pass that raised it (KHR_debug
  // has printed the failing call already). Release builds look once per frame (step_frame).
  gl::check_gl_errors_lazily([&] {
    return in_frame_ ? fmt::format("after the pass {} (substep {} of frame {})", program.name(), substep_ + 1,
                                   guard_.frame() + 1)
                     : fmt::format("after the pass {}", program.name());
  });
#endif
}

void GpuSimulator::compute_wind_forces() {
  dispatch(compute_wind_forces_);
  // advance (or accumulate_forces) reads the wind forces next.
  barrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void GpuSimulator::accumulate_forces() {
  dispatch(accumulate_forces_);
  // integrate reads the forces next.
  barrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void GpuSimulator::integrate() {
  dispatch(integrate_);
  // collide_self / collide_objects read the new positions and displacements next.
  barrier(kComputeReads);
}

void GpuSimulator::advance(bool then_collide_objects) {
  const bool listed = then_collide_objects && uses_contact_list();
  if (listed) start_contact_list();
  advance_.set(advance_collide_objects_, int(then_collide_objects));
  dispatch(advance_);
  swap_positions();
  // The hash passes or the constraints read the new positions next (or collide_objects the
  // listed ones, its workgroups from the list's header: COMMAND); the next advance writes the
  // old ones (now the output buffer) after this pass read them.
  barrier(kComputeReads | (listed ? GL_COMMAND_BARRIER_BIT : 0));
  if (listed) collide_listed();
}

void GpuSimulator::count_cells() {
  cell_count_.clear_to_zero();
  dispatch(count_cells_);
  // scan_cells copies the counts next (a buffer copy, hence BUFFER_UPDATE).
  barrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GpuSimulator::scan_cells() {
  cell_start_.copy_from(cell_count_, 0, 0, table_size_ * sizeof(uint32_t));
  scan_.scan(cell_start_, table_size_);  // ends with a barrier for fill_cells
}

void GpuSimulator::fill_cells() {
  cell_count_.clear_to_zero();  // reused as the per-bucket cursors
  dispatch(fill_cells_);
  // sort_cells reads the entries next.
  barrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void GpuSimulator::sort_cells() {
  bind_for_pass();
  sort_cells_.dispatch(gl::workgroups_for(table_size_, WORKGROUP_SIZE));
  dispatched(sort_cells_);
  // collide_self reads the starts and the positions in cell order next.
  barrier(kComputeReads);
}

void GpuSimulator::collide_self(bool then_collide_objects) {
  count_cells();
  scan_cells();
  fill_cells();
  sort_cells();
  resolve_self_contacts(then_collide_objects);
}

void GpuSimulator::resolve_self_contacts(bool then_collide_objects) {
  resolve_self_contacts_.set(resolve_collide_objects_, int(then_collide_objects));
  dispatch(resolve_self_contacts_);
  // Jacobi: the output becomes the positions; collide_objects or the constraints read them
  // next. The next substep's count_cells clears the cursors fill_cells wrote, and scan_cells
  // copies over the starts the scan wrote: buffer updates after shader writes (BUFFER_UPDATE).
  swap_positions();
  barrier(kComputeReads | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GpuSimulator::collide_objects() {
  if (!constants_.has_colliders()) return;
  dispatch(collide_objects_);
  // solve_length_constraints reads the projected positions next.
  barrier(kComputeReads);
}

void GpuSimulator::solve_length_constraint_colour(int colour) {
  bind_for_pass();
  dispatch_colour(solve_length_constraints_, length_colour_, colour);
}

void GpuSimulator::dispatch_colour(gl::Program& program, ColourUniforms where, int colour, GLbitfield also) {
  const uint32_t first = model_.colour_start[colour], count = model_.colour_start[colour + 1] - first;
  if (count == 0) return;  // a grid too narrow for this colour
  program.set(where.first, first);
  program.set(where.count, count);
  program.dispatch(gl::workgroups_for(count, WORKGROUP_SIZE));
  dispatched(program);
  // The next colour (or the next substep's first pass) reads these positions and displacements,
  // and xpbd's next predict the multipliers.
  barrier(kComputeReads | also);
}

void GpuSimulator::length_constraint_passes(int passes) {
  bind_for_pass();
  for (int pass = 0; pass < passes; ++pass)
    for (int colour = 0; colour < model_.colours(); ++colour) {
      if (!constants_.colour_enabled(model_, colour)) continue;
      dispatch_colour(solve_length_constraints_, length_colour_, colour);
    }
}

void GpuSimulator::solve_length_constraints() { length_constraint_passes(constants_.iterations); }

void GpuSimulator::predict(bool then_collide_objects) {
  const bool listed = then_collide_objects && uses_contact_list();
  if (listed) start_contact_list();
  predict_.set(predict_collide_objects_, int(then_collide_objects));
  dispatch(predict_);
  // The hash passes or the constraints read the predicted positions and displacements next
  // (under multigrid compute_residuals reads the offsets too, through their view), or first
  // collide_objects the listed ones, its workgroups from the list's header (COMMAND).
  barrier(kComputeReads | (listed ? GL_COMMAND_BARRIER_BIT : 0));
  if (listed) collide_listed();
}

void GpuSimulator::solve_distance_constraint_colour(int colour) {
  bind_for_pass();
  const bool listed = uses_contact_list() && model_.colour_start[colour + 1] > model_.colour_start[colour];
  if (listed) start_contact_list();
  // With the list, collide_objects next reads its workgroups from the header this colour wrote.
  dispatch_colour(solve_distance_constraints_, distance_colour_, colour, listed ? GL_COMMAND_BARRIER_BIT : 0);
  if (listed) collide_listed(false);
}

void GpuSimulator::solve_distance_constraints() {
  for (int colour = 0; colour < model_.colours(); ++colour)
    if (constants_.colour_enabled(model_, colour)) solve_distance_constraint_colour(colour);
}

void GpuSimulator::compute_normals() {
  dispatch(compute_normals_);
  // The vertex shader pulls normals (and a read-back may follow).
  barrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GpuSimulator::step() {
  // collide_objects reads only a particle's own position and displacement, so it rides
  // along with the last per-particle pass before the constraints.
  const bool colliders = constants_.has_colliders();
  // Moving colliders, pins and gusts: the small parameter upload of this substep's time.
  if (constants_.timeline.moves()) apply_substep_time();
  ensure_multigrid();  // (after a live edit rebuilt the hierarchy) before the bindings
  bind_all();  // once: nothing in the step binds over these (swap_positions rebinds its two)
  {
  const ScopedFlag in_step(in_step_);
  const bool objects_first = colliders && !constants_.self_collision;
  if (constants_.wind_enabled) compute_wind_forces();  // advance or predict add them
  if (constants_.xpbd) {
    predict(objects_first);
    if (constants_.self_collision) collide_self(colliders);
    if (constants_.multigrid)
      solve_multigrid();
    else
      solve_distance_constraints();
    enforce_stretch_limit();  // stretch_passes: the limit holds after either sweep
  } else {
    advance(objects_first);
    if (constants_.self_collision) collide_self(colliders);
    solve_length_constraints();
  }
  }
  time_ += dt_;  // per substep, exactly as CpuBackend counts it
}

std::string GpuSimulator::pass_list() const {
  std::string passes = constants_.wind_enabled ? "compute_wind_forces, " : "";
  passes += constants_.xpbd ? "predict" : "advance";
  if (!constants_.self_collision && uses_contact_list()) passes += ", collide_objects (the listed masses)";
  if (constants_.self_collision) passes += ", collide_self (count_cells, scan_cells, fill_cells, sort_cells, resolve_self_contacts)";
  passes += constants_.multigrid ? ", solve_multigrid (compute_residuals, restrict_residuals, smooth_corrections, "
                                   "cycle_small_levels, prolong_corrections, prolong_to_cloth, relax_vertices)"
             : constants_.xpbd   ? ", solve_distance_constraints"
                                 : ", solve_length_constraints";
  if (constants_.stretch_passes_max > constants_.stretch_passes)
    passes += ", enforce_stretch_limit (solve_length_constraints, then arm_stretch_pass and the watched passes)";
  else if (constants_.stretch_passes > 0)
    passes += ", enforce_stretch_limit (solve_length_constraints)";
  return passes;
}

void GpuSimulator::step_frame() {
  const int frame = guard_.frame() + 1;
  // GL errors, in release builds too: glGetError reads the context's error flags, with no wait
  // for the GPU (unlike glFinish) and no read-back. First what was raised since the previous
  // frame's check by someone else (the renderer, a read-back, an edit), so it is not blamed on
  // the passes; then, after the passes, theirs.
  gl::check_gl_errors_lazily([&] {
    return fmt::format("before frame {} on the GPU: raised by a GL call outside the simulation since the previous "
                       "frame's check (rendering, a read-back or an edit), not by its passes",
                       frame);
  });
  {
    const ScopedFlag in_frame(in_frame_);
    for (substep_ = 0; substep_ < int(constants_.steps); ++substep_) step();
    compute_normals();
  }
  guard_.check(positions_);
  gl::check_gl_errors_lazily([&] {
    return fmt::format("in frame {} on the GPU: raised by one of the frame's passes ({} substeps of {}; then "
                       "compute_normals, check_divergence, keep_last_good). A debug build (-DCMAKE_BUILD_TYPE=Debug) "
                       "names the pass and the GL call",
                       frame, int(constants_.steps), pass_list());
  });
}

int GpuSimulator::dispatches_per_substep() const {
  int enabled_colours = 0;
  for (int colour = 0; colour < model_.colours(); ++colour) enabled_colours += enabled_colour(colour);
  const int self = constants_.self_collision ? 4 + scan_.dispatches(table_size_) : 0;  // count, fill, sort, collide + scan
  // xpbd: predict, then one solve of every enabled colour; classic: advance, then the colours
  // once per constraint iteration; with wind, its pass first.
  // stretch_passes: the limit's passes after either xpbd sweep (0 for classic); with settling
  // passes, up to stretch_passes_max of them, each after its arm_stretch_pass (the watched passes
  // are dispatched whether they run or not: a skipped one's workgroups are 0).
  const int fixed = constants_.stretch_passes, most = constants_.stretch_passes_max;
  const int limit = most > fixed ? most * enabled_colours + most - std::max(fixed, 1) + 1 : fixed * enabled_colours;
  // The first pass's collide_objects over the contact list, where the step collides through it.
  const int listed = !constants_.self_collision && uses_contact_list() ? 1 : 0;
  if (constants_.multigrid) return 1 + listed + int(constants_.wind_enabled) + self + multigrid_dispatches() + limit;
  // xpbd's sweep pushes each colour's listed masses out after it.
  const int sweep = constants_.xpbd ? (uses_contact_list() ? 2 : 1) * enabled_colours : constants_.iterations * enabled_colours;
  return 1 + listed + int(constants_.wind_enabled) + self + sweep + limit;
}

}  // namespace clothsim

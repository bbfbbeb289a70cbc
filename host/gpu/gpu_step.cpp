// The passes and the step: one dispatch per pass, each followed by a barrier that says who
// reads next. Bindings are made once per step (bind_all); a pass called on its own binds first.
#include "gpu_simulator.hpp"

namespace clothsim {
namespace {

// What a pass's readers need after it wrote: storage-buffer reads and texel fetches (the
// passes read particle data through texel views, compute/particle_views.glsl).
constexpr GLbitfield kComputeReads = GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;

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
  ++counters_.dispatches;
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
  advance_.set(advance_collide_objects_, int(then_collide_objects));
  dispatch(advance_);
  swap_positions();
  // The hash passes or the constraints read the new positions next; the next advance
  // writes the old ones (now the output buffer) after this pass read them.
  barrier(kComputeReads);
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
  ++counters_.dispatches;
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

void GpuSimulator::dispatch_colour(gl::Program& program, ColourUniforms where, int colour) {
  const uint32_t first = model_.colour_start[colour], count = model_.colour_start[colour + 1] - first;
  if (count == 0) return;  // a grid too narrow for this colour
  program.set(where.first, first);
  program.set(where.count, count);
  program.dispatch(gl::workgroups_for(count, WORKGROUP_SIZE));
  ++counters_.dispatches;
  // The next colour (or the next substep's first pass) reads these positions and displacements.
  barrier(kComputeReads);
}

void GpuSimulator::solve_length_constraints() {
  bind_for_pass();
  for (int it = 0; it < constants_.iterations; ++it)
    for (int colour = 0; colour < model_.colours(); ++colour) {
      if (!constants_.colour_enabled(model_, colour)) continue;
      dispatch_colour(solve_length_constraints_, length_colour_, colour);
    }
}

void GpuSimulator::predict(bool then_collide_objects) {
  predict_.set(predict_collide_objects_, int(then_collide_objects));
  dispatch(predict_);
  // The hash passes or the constraints read the predicted positions and displacements next.
  barrier(kComputeReads);
}

void GpuSimulator::solve_distance_constraint_colour(int colour) {
  bind_for_pass();
  dispatch_colour(solve_distance_constraints_, distance_colour_, colour);
}

void GpuSimulator::solve_distance_constraints() {
  bind_for_pass();
  for (int colour = 0; colour < model_.colours(); ++colour) {
    if (!constants_.colour_enabled(model_, colour)) continue;
    dispatch_colour(solve_distance_constraints_, distance_colour_, colour);
  }
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
  bind_all();  // once: nothing in the step binds over these (swap_positions rebinds its two)
  in_step_ = true;
  const bool objects_first = colliders && !constants_.self_collision;
  if (constants_.wind.enabled) compute_wind_forces();  // advance or predict add them
  if (constants_.xpbd) {
    predict(objects_first);
    if (constants_.self_collision) collide_self(colliders);
    solve_distance_constraints();
  } else {
    advance(objects_first);
    if (constants_.self_collision) collide_self(colliders);
    solve_length_constraints();
  }
  in_step_ = false;
  time_ += dt_;  // per substep, exactly as CpuBackend counts it
}

void GpuSimulator::step_frame() {
  for (int k = 0; k < int(constants_.steps); ++k) step();
  compute_normals();
  guard_.check(positions_);
}

int GpuSimulator::dispatches_per_substep() const {
  int enabled_colours = 0;
  for (int colour = 0; colour < model_.colours(); ++colour) {
    const uint32_t springs = model_.colour_start[colour + 1] - model_.colour_start[colour];
    enabled_colours += springs > 0 && constants_.colour_enabled(model_, colour);
  }
  const int self = constants_.self_collision ? 4 + scan_.dispatches(table_size_) : 0;  // count, fill, sort, collide + scan
  // xpbd: predict, then one solve of every enabled colour; classic: advance, then the colours
  // once per constraint iteration; with wind, its pass first.
  return 1 + int(constants_.wind.enabled) + self + (constants_.xpbd ? 1 : constants_.iterations) * enabled_colours;
}

}  // namespace clothsim

// run(PassId): a pass of the table as the step runs it, and the sweeps made of its rows. Each
// dispatch goes through dispatch_row, which sizes it and issues its row's barrier.
#include "gpu_passes.hpp"

namespace clothsim {

void GpuPasses::run(PassId pass, PassArgs a) {
  if (row(pass).build == Build::multigrid) ensure_multigrid();
  bind_for_pass();
  switch (pass) {
    case PassId::advance:
    case PassId::predict: return first_pass(pass, a.collide_objects);
    case PassId::collide_listed: return dispatch_row(pass);
    case PassId::count_cells:
    case PassId::fill_cells: state_.cell_count_.clear_to_zero(); break;  // fill_cells: reused as the per-bucket cursors
    case PassId::scan_cells:
      state_.cell_start_.copy_from(state_.cell_count_, 0, 0, state_.table_size_ * sizeof(uint32_t));
      scan_.scan(state_.cell_start_, state_.table_size_);  // ends with a barrier for fill_cells
      return;
    case PassId::resolve_self_contacts:
      programs_[size_t(pass)].set(flag_[size_t(pass)], int(a.collide_objects));
      dispatch_row(pass);
      state_.swap_positions();  // Jacobi: the output becomes the positions
      return;
    case PassId::collide_objects:
      if (!constants_.has_colliders()) return;
      break;
    case PassId::skin_colliders:
    case PassId::fit_collider_boxes:  // they write through the scan's point: bound again before each use
      state_.skinned_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SKINNED);
      break;
    case PassId::solve_length_constraints:
      if (a.colour >= 0) return colour_pass(pass, a.colour);
      return length_constraint_passes(constants_.iterations);
    case PassId::stretch_fixed_passes:
    case PassId::arm_stretch_pass:
    case PassId::stretch_watched_passes: return enforce_stretch_limit();
    case PassId::restrict_residuals:
    case PassId::prolong_corrections:
    case PassId::smooth_corrections:
    case PassId::relax_vertices: return level_pass(pass, a);
    case PassId::cycle_small_levels:
      if (constants_.hierarchy->levels.empty()) return;
      break;  // its table (levels, vertices, colours) is set with the hierarchy (ensure_multigrid)
    default: break;
  }
  dispatch_row(pass);
}

void GpuPasses::first_pass(PassId pass, bool then_collide_objects) {
  const bool listed = then_collide_objects && uses_contact_list();
  if (listed) start_contact_list();
  programs_[size_t(pass)].set(flag_[size_t(pass)], int(then_collide_objects));
  dispatch_row(pass, {}, listed);
  // advance writes the positions out of place: the output becomes the positions (predict
  // writes them in place).
  if (pass == PassId::advance) state_.swap_positions();
  // The listed collisions: their own row in simulate --profile, taken off the first pass's.
  if (listed) timed("collide_objects (first)", [&] { dispatch_row(PassId::collide_listed); });
}

void GpuPasses::colour_pass(PassId pass, int colour) {
  const uint32_t first = state_.model_.colour_start[colour], count = state_.model_.colour_start[colour + 1] - first;
  dispatch_row(pass, {first, count});
}

void GpuPasses::length_constraint_passes(int passes, PassId row) {
  bind_for_pass();
  for (int pass = 0; pass < passes; ++pass)
    for (int colour = 0; colour < state_.model_.colours(); ++colour)
      if (constants_.colour_enabled(state_.model_, colour)) colour_pass(row, colour);
}

void GpuPasses::collide_self(bool then_collide_objects) {
  for (PassId stage : {PassId::count_cells, PassId::scan_cells, PassId::fill_cells, PassId::sort_cells}) run(stage);
  run(PassId::resolve_self_contacts, {.collide_objects = then_collide_objects});
}

}  // namespace clothsim

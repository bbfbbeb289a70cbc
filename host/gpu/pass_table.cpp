// The pass table (pass_table.hpp): one row per pass, in a substep's order.
#include "pass_table.hpp"

#include <algorithm>

namespace clothsim {
namespace {

constexpr GLbitfield kSsbo = GL_SHADER_STORAGE_BARRIER_BIT, kUpdate = GL_BUFFER_UPDATE_BARRIER_BIT;
constexpr GLbitfield kCommand = GL_COMMAND_BARRIER_BIT;
using P = PassId;
using D = Domain;
using B = Build;
using C = Count;

}  // namespace

// name, file, build, program_of, domain, barrier, listed_barrier, need, unless, count, flag uniform,
// group, stage (GpuSimulator::step's entry and bench's row), who reads next.
const PassRow kPasses[kPassCount] = {
    {P::compute_wind_forces, "compute_wind_forces", "compute_wind_forces", B::always, P::compute_wind_forces,
     D::particles, kSsbo, 0, kWind, 0, C::once, nullptr, nullptr, true,
     "advance or predict (or accumulate_forces) add the wind forces next"},
    {P::advance, "advance", "advance", B::always, P::advance, D::particles, kComputeReads, kCommand, kClassic, 0,
     C::once, "u_collide_objects", nullptr, true,
     "the hash passes or the constraints read the new positions (or collide_objects the listed ones, its "
     "workgroups from the list's header: COMMAND); the next advance writes the old ones after this pass read them"},
    {P::predict, "predict", "predict", B::always, P::predict, D::particles, kComputeReads, kCommand, kXpbd, 0,
     C::once, "u_collide_objects", nullptr, true,
     "the hash passes or the constraints read the predicted positions and displacements (multigrid's "
     "compute_residuals the offsets too), or first collide_objects the listed ones (COMMAND)"},
    {P::collide_listed, "collide_objects", "collide_objects", B::listed, P::collide_listed, D::contact_list,
     kComputeReads | kUpdate, 0, kListed, kSelf, C::once, nullptr, nullptr, false,
     "the hash passes or the constraints read the positions; the next start_contact_list rewrites the header "
     "this pass read (a buffer update)"},
    {P::count_cells, "count_cells", "count_cells", B::always, P::count_cells, D::particles, kUpdate, 0, kSelf, 0,
     C::once, nullptr, "collide_self", true, "scan_cells copies the counts (a buffer copy: BUFFER_UPDATE)"},
    {P::scan_cells, "scan_cells", "scan_cells", B::none, P::scan_cells, D::scan, 0, 0, kSelf, 0, C::scan, nullptr,
     "collide_self", true, "fill_cells reads the starts: the scan ends with its own barrier"},
    {P::fill_cells, "fill_cells", "fill_cells", B::always, P::fill_cells, D::particles, kSsbo, 0, kSelf, 0, C::once,
     nullptr, "collide_self", true, "sort_cells reads the entries"},
    {P::sort_cells, "sort_cells", "sort_cells", B::always, P::sort_cells, D::hash_table, kComputeReads, 0, kSelf, 0,
     C::once, nullptr, "collide_self", true, "resolve_self_contacts reads the starts and the positions in cell order"},
    {P::resolve_self_contacts, "resolve_self_contacts", "resolve_self_contacts", B::always, P::resolve_self_contacts,
     D::particles, kComputeReads | kUpdate, 0, kSelf, 0, C::once, "u_collide_objects", "collide_self", true,
     "Jacobi: the output becomes the positions, which collide_objects or the constraints read; the next "
     "count_cells clears the cursors and scan_cells copies over the starts (buffer updates)"},
    {P::solve_length_constraints, "solve_length_constraints", "solve_length_constraints", B::always,
     P::solve_length_constraints, D::colour, kComputeReads, 0, kClassic, 0, C::iterations_x_colours, nullptr,
     nullptr, true, "the next colour (or the next substep's first pass) reads these positions and displacements"},
    {P::solve_distance_constraints, "solve_distance_constraints", "solve_distance_constraints", B::always,
     P::solve_distance_constraints, D::colour, kComputeReads, kCommand, kXpbd, kMultigrid, C::enabled_colours,
     nullptr, nullptr, true,
     "the next colour reads these positions, xpbd's next predict the multipliers; or first collide_objects the "
     "listed masses (COMMAND)"},
    {P::compute_residuals, "compute_residuals", "compute_residuals", B::multigrid, P::compute_residuals,
     D::particles, kComputeReads, 0, kMultigrid, 0, C::once, nullptr, "solve_multigrid", true,
     "restrict_residuals reads them through their view"},
    {P::restrict_residuals, "restrict_residuals", "restrict_residuals", B::multigrid, P::restrict_residuals,
     D::range, kComputeReads, 0, kMultigrid, 0, C::large_levels, nullptr, "solve_multigrid", true,
     "smooth_corrections reads the right-hand sides and the zeroed corrections"},
    {P::cycle_small_levels, "cycle_small_levels", "cycle_small_levels", B::multigrid, P::cycle_small_levels,
     D::one_workgroup, kComputeReads, 0, kMultigrid, 0, C::small_cycle, nullptr, "solve_multigrid", false,
     "prolong_corrections (or prolong_to_cloth) reads the corrections through their view"},
    {P::prolong_corrections, "prolong_corrections", "prolong_corrections", B::multigrid, P::prolong_corrections,
     D::range, kComputeReads, 0, kMultigrid, 0, C::large_levels, nullptr, "solve_multigrid", false,
     "smooth_corrections reads the corrections through their view"},
    {P::smooth_corrections, "smooth_corrections", "smooth_corrections", B::multigrid, P::smooth_corrections,
     D::range, kComputeReads, 0, kMultigrid, 0, C::large_level_sweeps, nullptr, "solve_multigrid", false,
     "the next colour reads these corrections through their view"},
    {P::prolong_to_cloth, "prolong_to_cloth", "prolong_to_cloth", B::multigrid, P::prolong_to_cloth, D::particles,
     kComputeReads, 0, kMultigrid, 0, C::once, nullptr, "solve_multigrid", true,
     "relax_vertices reads the positions (views), displacements and offsets"},
    {P::relax_vertices, "relax_vertices", "relax_vertices", B::multigrid, P::relax_vertices, D::range,
     kComputeReads, kCommand, kMultigrid, 0, C::fine_colours, nullptr, "solve_multigrid", true,
     "the next colour (or the next substep's first pass) reads these positions, or first collide_objects the "
     "listed ones (COMMAND)"},
    {P::collide_listed_frictionless, "collide_objects", "collide_objects", B::frictionless,
     P::collide_listed_frictionless, D::contact_list, kComputeReads | kUpdate, 0, kXpbd | kListed, 0,
     C::listed_sweep_colours, nullptr, nullptr, false,
     "the next colour reads the positions; the next start_contact_list rewrites the header (a buffer update)"},
    {P::stretch_fixed_passes, "solve_length_constraints", "solve_length_constraints", B::shared,
     P::solve_length_constraints, D::colour, kComputeReads, 0, kStretch, 0, C::fixed_stretch_sweeps, nullptr,
     "enforce_stretch_limit", true, "the next colour (or the next substep's first pass) reads these positions"},
    {P::arm_stretch_pass, "arm_stretch_pass", "arm_stretch_pass", B::settling, P::arm_stretch_pass,
     D::one_workgroup, kCommand | kSsbo, 0, kSettling, 0, C::arms, "u_first_watched", "enforce_stretch_limit", false,
     "the watched pass reads its workgroups from what the arm wrote (COMMAND) and stores the flag the arm "
     "cleared through the same storage buffer (SHADER_STORAGE)"},
    {P::stretch_watched_passes, "solve_length_constraints", "solve_length_constraints", B::settling,
     P::stretch_watched_passes, D::stretch_control, kComputeReads, 0, kSettling, 0, C::watched_sweeps, nullptr,
     "enforce_stretch_limit", false, "the next colour reads these positions; the next arm reads the flag"},
    {P::compute_normals, "compute_normals", "compute_normals", B::always, P::compute_normals, D::particles,
     kSsbo | kUpdate, 0, kPerFrame, 0, C::none, nullptr, nullptr, true,
     "the vertex shader pulls the normals (and a read-back may follow)"},
    {P::accumulate_forces, "accumulate_forces", "accumulate_forces", B::always, P::accumulate_forces,
     D::particles, kSsbo, 0, kCheckOnly, 0, C::none, nullptr, nullptr, false, "integrate reads the forces"},
    {P::integrate, "integrate", "integrate", B::always, P::integrate, D::particles, kComputeReads, 0, kCheckOnly, 0,
     C::none, nullptr, nullptr, false, "collide_self or collide_objects read the new positions and displacements"},
    {P::collide_objects, "collide_objects", "collide_objects", B::always, P::collide_objects, D::particles,
     kComputeReads, 0, kCheckOnly, 0, C::none, nullptr, nullptr, false,
     "solve_length_constraints reads the projected positions"},
};

static_assert(sizeof(kPasses) / sizeof(kPasses[0]) == kPassCount);

bool runs(const PassRow& r, uint16_t features) { return (features & r.need) == r.need && (features & r.unless) == 0; }

const char* stage_name(const PassRow& r) {
  return r.id == PassId::restrict_residuals ? "cycle_levels" : r.id == PassId::stretch_fixed_passes ? "enforce_stretch_limit" : r.name;
}

int dispatches_of(const PassRow& r, const SubstepShape& s) {
  if (!runs(r, s.features)) return 0;
  const int fixed = std::max(s.stretch_passes, 1), settling = s.stretch_passes_max - fixed + 1;
  switch (r.count) {
    case Count::once: return 1;
    case Count::scan: return s.scan_dispatches;
    case Count::iterations_x_colours: return s.iterations * s.enabled_colours;
    case Count::enabled_colours: return s.enabled_colours;
    case Count::listed_sweep_colours: return s.listed_sweep_colours;
    case Count::large_levels: return s.large_levels;
    case Count::small_cycle: return s.levels > 0 ? 1 : 0;
    case Count::large_level_sweeps: return s.large_level_colours;
    case Count::fine_colours: return s.fine_colours;
    case Count::fixed_stretch_sweeps:
      return (s.features & kSettling ? fixed - 1 : s.stretch_passes) * s.enabled_colours;
    case Count::arms: return settling;
    case Count::watched_sweeps: return settling * s.enabled_colours;
    case Count::none: return 0;
  }
  return 0;
}

int dispatches_per_substep(const SubstepShape& s) {
  int total = 0;
  for (const PassRow& r : kPasses) total += dispatches_of(r, s);
  return total;
}

std::string pass_list(const SubstepShape& s) {
  std::string out;
  const char* open = nullptr;  // the group whose parenthesis is open
  for (const PassRow& r : kPasses) {
    if (dispatches_of(r, s) == 0 && r.count != Count::scan) continue;
    if (!runs(r, s.features)) continue;
    if (open && (!r.group || std::string(r.group) != open)) out += ")", open = nullptr;
    if (!out.empty()) out += ", ";
    if (r.group && !open) out += std::string(r.group) + " (", open = r.group;
    out += r.name;
  }
  if (open) out += ")";
  return out;
}

}  // namespace clothsim

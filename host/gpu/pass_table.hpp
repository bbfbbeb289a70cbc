// The GPU's passes as data (issue 42, item 3): one row per pass, in the order a substep runs
// them. The row drives loading (GpuPasses::load_passes, ensure_multigrid, the settling passes),
// the dispatch (its size from `domain`, its barrier from `barrier` and `listed_barrier`),
// the step (GpuSimulator::step runs the rows marked `stage`), the pass list of messages
// (pass_list), dispatches_per_substep (`count`), the pass checks (pass_check.cpp runs each
// row's CPU twin, `twin`, and compares `compare`; a row it does not check by hand it checks
// after the others) and bench's per-pass rows (`stage` again). A new pass is a .comp file, its
// CPU twin (reference .cpp, reference.hpp), and its PassId and row here: this header is the
// whole table (docs/code-layout.md, "Adding a GPU pass").
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>

#include "program.hpp"
#include "reference/reference.hpp"

namespace clothsim {

// Every pass, in the table's (the substep's) order; the enumerator is the row's index.
enum class PassId : uint8_t {
  skin_colliders, fit_collider_boxes, compute_wind_forces, advance, predict, collide_listed, count_cells, scan_cells, fill_cells, sort_cells,
  resolve_self_contacts, solve_length_constraints, compute_residuals,
  restrict_residuals, cycle_small_levels, prolong_corrections, smooth_corrections, prolong_to_cloth, relax_vertices,
  stretch_fixed_passes, arm_stretch_pass, stretch_watched_passes, limit_speed, compute_normals,
  accumulate_forces, integrate, collide_objects, count_
};
inline constexpr size_t kPassCount = size_t(PassId::count_);

// How many workgroups one dispatch of the pass has.
enum class Domain : uint8_t {
  particles,       // one invocation per particle
  skinned_vertices,  // one per skinned collider vertex (Constants::skin_vertices)
  skin_supers,     // one per super-group of the skinned colliders' tree of boxes (Constants::skin_supers)
  hash_table,      // one per bucket of the spatial hash
  colour,          // u_first, u_count: a colour's springs (an empty colour: no dispatch, no barrier)
  range,           // u_first, u_count: a coarse level or colour, a fine colour (empty: no dispatch, the barrier stays)
  contact_list,    // indirect: the contact list's header (gpu_contacts.cpp)
  stretch_control, // indirect: a colour's entry of the settling control (gpu_stretch_limit.cpp)
  one_workgroup,   // its own barriers order its steps
  scan,            // not ours: the prefix scan's dispatches (prefix_scan.cpp)
};

// When a pass's program is compiled, with which extra defines.
enum class Build : uint8_t {
  always,          // at construction and again when the shader features change (load_passes)
  listed,          // always, with LISTED (collide_objects over the contact list)
  multigrid,       // with the multigrid solver's first pass (ensure_multigrid), its constants defined
  settling,        // with the first settling pass (stretch_passes_max above stretch_passes)
  shared,          // not compiled: runs `program_of`'s program
  none,            // no program of ours (the scan)
};

// What a scene runs, for `need` and `unless` (a row runs when it has all of need and none of unless).
enum Feature : uint16_t {
  kWind = 1, kClassic = 2, kFabric = 4, kSelf = 16, kListed = 32, kStretch = 64, kSettling = 128,
  kCheckOnly = 256,  // run only by the pass checks (a row no substep runs)
  kPerFrame = 512,   // once per frame, after the substeps
  kSpeedLimit = 1024,  // simulation.max_speed above 0
  kSkinned = 2048,     // a skinned mesh collider (mesh.animation)
};

// A scene's features (`listed`: collide_objects runs over the contact list).
inline uint16_t features_of(const Constants<float>& c, bool listed) {
  return uint16_t((c.wind_enabled ? kWind : 0) | (c.multigrid ? kFabric : kClassic) |
                  (c.self_collision ? kSelf : 0) | (listed ? kListed : 0) | (c.stretch_passes_max > 0 ? kStretch : 0) |
                  (c.stretch_passes_max > c.stretch_passes ? kSettling : 0) | (c.max_move > 0.f ? kSpeedLimit : 0) |
                  (c.skin_vertices > 0 ? kSkinned : 0));
}

// How many dispatches of the row one substep issues (dispatches_per_substep, pass_check).
enum class Count : uint8_t {
  once, scan, iterations_x_colours, large_levels, small_cycle,
  large_level_sweeps, fine_colours, fixed_stretch_sweeps, arms, watched_sweeps, none,
};

// A pass's CPU twin: from the state before the pass to the state after it.
using Twin = void (*)(const ClothModel&, const Constants<float>&, State<float>&);

// What a pass's check compares (pass_check.cpp's streams).
enum class Compare : uint8_t {
  none,
  positions,   // every position, then every displacement
  wind,        // the wind forces, as the displacement they cause in one substep
  forces,      // the forces, the same
  normals,     // the vertex normals
};

struct PassRow {
  PassId id;
  const char* name;     // = its .comp file's stem (but for the variants) = its CPU twin's name
  const char* file;     // the .comp file's stem
  Build build;
  PassId program_of;    // Build::shared: whose program it runs; otherwise itself
  Domain domain;
  GLbitfield barrier;         // after every dispatch
  GLbitfield listed_barrier;  // added where the contact list's collide_objects follows (its indirect read)
  uint16_t need, unless;      // Feature bits: when a substep runs it
  Count count;
  const char* flag_uniform;   // an int uniform set before the dispatch, or nullptr
  const char* group;          // the step-level pass it belongs to (pass_list), or nullptr
  bool stage;                 // an entry of GpuSimulator::step and a row of bench
  const char* reads_next;     // who reads what it wrote: why `barrier` is what it is
  Twin twin = nullptr;        // its CPU twin, for the pass checks (pass_check.cpp)
  Compare compare = Compare::none;  // what its check compares
};

// What a pass's readers need after it wrote: storage-buffer reads and texel fetches (the
// passes read particle data through texel views, compute/particle_views.glsl).
inline constexpr GLbitfield kComputeReads = GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;

// The rows. A pass's CPU twin (`twin`, run by the pass checks from the CPU's state before the
// pass) and what the check compares (`compare`); a row without a twin is checked by hand in
// pass_check.cpp (the hash's stages, multigrid's levels, the settling passes) or not alone.
namespace pass_rows {
constexpr GLbitfield kSsbo = GL_SHADER_STORAGE_BARRIER_BIT, kUpdate = GL_BUFFER_UPDATE_BARRIER_BIT;
constexpr GLbitfield kCommand = GL_COMMAND_BARRIER_BIT;
using P = PassId;
using D = Domain;
using B = Build;
using C = Count;
using K = Compare;
// A twin of another signature, as a Twin.
constexpr Twin kCollideObjects = [](const ClothModel&, const Constants<float>& c, State<float>& s) { collide_objects(c, s); };
constexpr Twin kComputeNormals = [](const ClothModel& m, const Constants<float>&, State<float>& s) { compute_normals(m, s); };

// name, file, build, program_of, domain, barrier, listed_barrier, need, unless, count, flag uniform,
// group, stage (GpuSimulator::step's entry and bench's row), who reads next.
inline constexpr PassRow kPasses[] = {
    {P::skin_colliders, "skin_colliders", "skin_colliders", B::always, P::skin_colliders, D::skinned_vertices, kSsbo,
     0, kSkinned, 0, C::once, nullptr, "skin_colliders", true,
     "fit_collider_boxes reads the skinned vertices through the same storage buffer"},
    {P::fit_collider_boxes, "fit_collider_boxes", "fit_collider_boxes", B::always, P::fit_collider_boxes,
     D::skin_supers, kComputeReads, 0, kSkinned, 0, C::once, nullptr, "skin_colliders", true,
     "the collisions read the skinned vertices and the boxes through their views (and skin_colliders' writes, "
     "before this barrier, with them)"},
    {P::compute_wind_forces, "compute_wind_forces", "compute_wind_forces", B::always, P::compute_wind_forces,
     D::particles, kSsbo, 0, kWind, 0, C::once, nullptr, nullptr, true,
     "advance or predict (or accumulate_forces) add the wind forces next", &compute_wind_forces<float>, K::wind},
    {P::advance, "advance", "advance", B::always, P::advance, D::particles, kComputeReads, kCommand, kClassic, 0,
     C::once, "u_collide_objects", nullptr, true,
     "the hash passes or the constraints read the new positions (or collide_objects the listed ones, its "
     "workgroups from the list's header: COMMAND); the next advance writes the old ones after this pass read them", &advance<float>, K::positions},
    {P::predict, "predict", "predict", B::always, P::predict, D::particles, kComputeReads, kCommand, kFabric, 0,
     C::once, "u_collide_objects", nullptr, true,
     "the hash passes or the constraints read the predicted positions and displacements (multigrid's "
     "compute_residuals the offsets too), or first collide_objects the listed ones (COMMAND)", &predict<float>, K::positions},
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
     nullptr, true, "the next colour (or the next substep's first pass) reads these positions and displacements",
     &solve_length_constraints<float>, K::positions},
    {P::compute_residuals, "compute_residuals", "compute_residuals", B::multigrid, P::compute_residuals,
     D::particles, kComputeReads, 0, kFabric, 0, C::once, nullptr, "solve_multigrid", true,
     "restrict_residuals reads them through their view"},
    {P::restrict_residuals, "restrict_residuals", "restrict_residuals", B::multigrid, P::restrict_residuals,
     D::range, kComputeReads, 0, kFabric, 0, C::large_levels, nullptr, "solve_multigrid", true,
     "smooth_corrections reads the right-hand sides and the zeroed corrections"},
    {P::cycle_small_levels, "cycle_small_levels", "cycle_small_levels", B::multigrid, P::cycle_small_levels,
     D::one_workgroup, kComputeReads, 0, kFabric, 0, C::small_cycle, nullptr, "solve_multigrid", false,
     "prolong_corrections (or prolong_to_cloth) reads the corrections through their view"},
    {P::prolong_corrections, "prolong_corrections", "prolong_corrections", B::multigrid, P::prolong_corrections,
     D::range, kComputeReads, 0, kFabric, 0, C::large_levels, nullptr, "solve_multigrid", false,
     "smooth_corrections reads the corrections through their view"},
    {P::smooth_corrections, "smooth_corrections", "smooth_corrections", B::multigrid, P::smooth_corrections,
     D::range, kComputeReads, 0, kFabric, 0, C::large_level_sweeps, nullptr, "solve_multigrid", false,
     "the next colour reads these corrections through their view"},
    {P::prolong_to_cloth, "prolong_to_cloth", "prolong_to_cloth", B::multigrid, P::prolong_to_cloth, D::particles,
     kComputeReads, 0, kFabric, 0, C::once, nullptr, "solve_multigrid", true,
     "relax_vertices reads the positions (views), displacements and offsets"},
    {P::relax_vertices, "relax_vertices", "relax_vertices", B::multigrid, P::relax_vertices, D::range,
     kComputeReads, 0, kFabric, 0, C::fine_colours, nullptr, "solve_multigrid", true,
     "the next colour (or the next substep's first pass) reads these positions"},
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
    {P::limit_speed, "limit_speed", "limit_speed", B::always, P::limit_speed, D::particles, kComputeReads, 0,
     kSpeedLimit, 0, C::once, nullptr, nullptr, true,
     "the next substep's first pass (or compute_normals) reads the positions and displacements", &limit_speed<float>,
     K::positions},
    {P::compute_normals, "compute_normals", "compute_normals", B::always, P::compute_normals, D::particles,
     kSsbo | kUpdate, 0, kPerFrame, 0, C::none, nullptr, nullptr, true,
     "the vertex shader pulls the normals (and a read-back may follow)", kComputeNormals, K::normals},
    {P::accumulate_forces, "accumulate_forces", "accumulate_forces", B::always, P::accumulate_forces,
     D::particles, kSsbo, 0, kCheckOnly, 0, C::none, nullptr, nullptr, false, "integrate reads the forces", &accumulate_forces<float>, K::forces},
    {P::integrate, "integrate", "integrate", B::always, P::integrate, D::particles, kComputeReads, 0, kCheckOnly, 0,
     C::none, nullptr, nullptr, false, "collide_self or collide_objects read the new positions and displacements", &integrate<float>,
     K::positions},
    {P::collide_objects, "collide_objects", "collide_objects", B::always, P::collide_objects, D::particles,
     kComputeReads, 0, kCheckOnly, 0, C::none, nullptr, nullptr, false,
     "solve_length_constraints reads the projected positions", kCollideObjects, K::positions},
};

}  // namespace pass_rows
using pass_rows::kPasses;

// The rows are in PassId's order, one per pass.
static_assert(std::size(kPasses) == kPassCount);
consteval bool rows_in_order() {
  for (size_t i = 0; i < kPassCount; ++i)
    if (size_t(kPasses[i].id) != i) return false;
  return true;
}
static_assert(rows_in_order(), "kPasses[i].id == PassId(i)");
inline const PassRow& row(PassId id) { return kPasses[size_t(id)]; }

// A scene's features, and what a substep's dispatch counts depend on.
struct SubstepShape {
  uint16_t features = 0;
  int enabled_colours = 0, iterations = 0, scan_dispatches = 0;
  int stretch_passes = 0, stretch_passes_max = 0;
  int large_levels = 0, levels = 0, fine_colours = 0;
  int large_level_colours = 0;  // the large levels' colours times kLevelSweeps
};
bool runs(const PassRow& r, uint16_t features);
// A stage row's name as an entry of the step (bench's row): restrict_residuals' stage is the
// whole V-cycle (cycle_levels), stretch_fixed_passes' the whole enforce_stretch_limit.
const char* stage_name(const PassRow& r);
int dispatches_of(const PassRow& r, const SubstepShape& s);  // in one substep
int dispatches_per_substep(const SubstepShape& s);
std::string pass_list(const SubstepShape& s);  // a substep's passes, for messages

}  // namespace clothsim

// The GPU's passes as data (issue 42, item 3): one row per pass, in the order a substep runs
// them. The row drives loading (GpuPasses::load_passes, ensure_multigrid, the settling passes),
// the dispatch (its size from `domain`, its barrier from `barrier` and `listed_barrier`),
// the step (GpuSimulator::step runs the rows marked `stage`), the pass list of messages
// (pass_list), dispatches_per_substep (`count`), the pass checks (pass_check.cpp names its
// results by the rows) and bench's per-pass rows (`stage` again). A new pass is a .comp file,
// its CPU twin, a row here (and its PassId), and a case in GpuPasses::run where it needs more
// than one dispatch of its row (docs/code-layout.md, "Adding a pass").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "program.hpp"

namespace clothsim {

// Every pass, in the table's (the substep's) order; the enumerator is the row's index.
enum class PassId : uint8_t {
  compute_wind_forces, advance, predict, collide_listed, count_cells, scan_cells, fill_cells, sort_cells,
  resolve_self_contacts, solve_length_constraints, solve_distance_constraints, compute_residuals,
  restrict_residuals, cycle_small_levels, prolong_corrections, smooth_corrections, prolong_to_cloth, relax_vertices,
  collide_listed_frictionless, stretch_fixed_passes, arm_stretch_pass, stretch_watched_passes, compute_normals,
  accumulate_forces, integrate, collide_objects, count_
};
inline constexpr size_t kPassCount = size_t(PassId::count_);

// How many workgroups one dispatch of the pass has.
enum class Domain : uint8_t {
  particles,       // one invocation per particle
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
  frictionless,    // always, with LISTED and FRICTIONLESS (the sweeps' push-out)
  multigrid,       // with the multigrid solver's first pass (ensure_multigrid), its constants defined
  settling,        // with the first settling pass (stretch_passes_max above stretch_passes)
  shared,          // not compiled: runs `program_of`'s program
  none,            // no program of ours (the scan)
};

// What a scene runs, for `need` and `unless` (a row runs when it has all of need and none of unless).
enum Feature : uint16_t {
  kWind = 1, kClassic = 2, kXpbd = 4, kMultigrid = 8, kSelf = 16, kListed = 32, kStretch = 64, kSettling = 128,
  kCheckOnly = 256,  // run only by the pass checks (a row no substep runs)
  kPerFrame = 512,   // once per frame, after the substeps
};

// How many dispatches of the row one substep issues (dispatches_per_substep, pass_check).
enum class Count : uint8_t {
  once, scan, iterations_x_colours, enabled_colours, listed_sweep_colours, large_levels, small_cycle,
  large_level_sweeps, fine_colours, fixed_stretch_sweeps, arms, watched_sweeps, none,
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
};

// What a pass's readers need after it wrote: storage-buffer reads and texel fetches (the
// passes read particle data through texel views, compute/particle_views.glsl).
inline constexpr GLbitfield kComputeReads = GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;

extern const PassRow kPasses[kPassCount];
inline const PassRow& row(PassId id) { return kPasses[size_t(id)]; }

// A scene's features, and what a substep's dispatch counts depend on.
struct SubstepShape {
  uint16_t features = 0;
  int enabled_colours = 0, iterations = 0, scan_dispatches = 0;
  int stretch_passes = 0, stretch_passes_max = 0;
  int listed_sweep_colours = 0;  // the sweep's colours with a push-out after them
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

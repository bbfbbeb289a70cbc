// The CPU reference: docs/design.md §1, one function per pass, named like the compute shader
// that mirrors it. Templated on the scalar so the same code runs in float (compared with
// the GPU bit for bit on llvmpipe) and in double (the noise floor of a float32 run).
// Every expression is written in the same operation order as its GLSL twin.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cloth/cloth.hpp"
#include "cloth/hierarchy.hpp"
#include "scene/scene.hpp"
#include "reference/pass_profile.hpp"
#include "reference/skin_lists.hpp"
#include "reference/timeline.hpp"
#include "reference/spatial_hash.hpp"
#include "../../../compute/layout.glsl"
#include "../../../compute/shared/vector.glsl"
#include "../../../compute/shared/springs.glsl"

namespace clothsim {

template <class R> using Vec3 = glm::vec<3, R>;
template <class R> using Vec4 = glm::vec<4, R>;

// |v| and a . b summed as (x*x + y*y) + z*z, written once for both backends.
using shared::dot3;
using shared::length3;

// The colliders as the passes read them, on both sides: the structs of compute/layout.glsl, on
// the scalar R (layout::SphereCollider is SphereColliderT<float>). keep = 1 - friction; motion =
// the collider's displacement over this substep (0: static, and then exactly the classic
// formulas run); mu: the friction coefficient itself, for fabric's Coulomb friction (docs/model.md,
// "Coulomb friction (fabric)"). A mesh collider's nodes are Constants::sdf[dims.w ...].
using layout::SphereColliderT;
using layout::PlaneColliderT;
using layout::MeshColliderT;
// A mesh collider's origin, in the w of its rows.
template <class R> Vec3<R> mesh_origin(const MeshColliderT<R>& m) { return Vec3<R>(m.row0.w, m.row1.w, m.row2.w); }
template <class R> void set_mesh_origin(MeshColliderT<R>& m, const Vec3<R>& o) {
  m.row0.w = o.x;
  m.row1.w = o.y;
  m.row2.w = o.z;
}

// The wind as the passes use it (docs/model.md, "Wind") is in the parameter block (wind_*,
// gust_*). The factors fold the constants of the formulas: drag = -rho C_d / 12 is -1/2 rho
// C_d, times 1/2 (the cross product of two edges is twice the area), times 1/3 (each corner
// gathers a third); lift likewise.

// The bounded contact's speed limit: a mass moves at most this fraction of the contact
// distance per substep (Constants::max_step).
inline constexpr double kMaxStepFraction = 0.25;

// The substep's control (issue 42, item 4): everything set_substep_time writes, the rest of
// Constants (the model) being fixed between edits. The colliders where they are at the
// substep's end, with their motion over it (the pose; their shape and friction are fixed over a
// run), and the block's fields (layout::SubstepControlT): pin_offset (where moving pins are at
// the substep's end), gust_phase (at its start) and seam_shrink (at its end). The GPU uploads
// Control<float>'s arrays and its block as they are, every substep when something moves.
template <class R> struct Control : layout::SubstepControlT<R> {
  std::vector<SphereColliderT<R>> spheres;
  std::vector<PlaneColliderT<R>> planes;
  std::vector<MeshColliderT<R>> meshes;
  // Skinned mesh colliders (docs/model.md, "Skinned and animated colliders"): the palette's
  // matrices (3 rows each, TEXTURE_SKIN_PALETTE) at the substep's start, then at its end; and
  // what skin_colliders makes of them (TEXTURE_SKINNED): every skinned vertex at the end, at
  // the start, in the bind pose, then every cluster's box (lo, hi) at the end, then every group's.
  std::vector<Vec4<R>> palette, skinned;
  double time = 0;  // s: where the colliders are (the substep's end; 0 before the first)
  const layout::SubstepControlT<R>& block() const { return *this; }  // as uploaded
};

// No triangle, no particle: an empty slot of State::nearest.
inline constexpr uint32_t kNoParticle = ~0u;

// Scene parameters converted once to R. The scalars the shaders read are the parameter block
// of compute/layout.glsl itself (StepParamsT<R>: gravity, dt2, stretch_limit, contact_distance,
// inv_cell, steps, max_step, inv_dt2, the wind's, bounded_contact, multigrid,
// ...); `control` the per-substep part (Control): the GPU uploads Constants<float>'s bytes.
// bounded_contact: fabric with self-collision, the bounded contact (docs/model.md, "Self-contact
// that holds"): predict clamps each substep's displacement to max_step (0: no clamp), and
// resolve_self_contacts keeps two masses min(contact_distance, their rest distance) apart, the
// rest distance from `rest` (the model's rest positions, rounded to R once).
// multigrid: the fabric solver, whose multigrid solve (docs/model.md) follows predict and whose
// hierarchy (hierarchy.hpp) is built once here; 0 for classic.

template <class R> struct Constants : layout::StepParamsT<R> {
  Control<R> control;  // what set_substep_time writes
  SkinLists<R> skin;
  std::vector<Vec3<R>> rest;
  std::vector<MaterialC<R>> materials;  // by cloth, Scene::cloths() order
  std::vector<R> mass;  // kg, per particle (particle_masses: follows a live density edit)
  std::vector<R> particle_ks;  // N/m, per particle: its cloth's ks (the self-contact's stiffness)
  std::vector<R> start_ks;     // N/m, per particle: MaterialC::start_ks (fabric's start and fold threshold)
  int iterations;
  int stretch_passes = 0;  // fabric: enforce_stretch_limit's passes after the sweep
  // fabric: enforce_stretch_limit's passes in all, the settling ones included (not above
  // stretch_passes: none settle)
  int stretch_passes_max = 0;
  bool self_collision;
  std::shared_ptr<const Hierarchy> hierarchy;
  std::shared_ptr<const std::vector<float>> sdf;  // every mesh's field, concatenated (shared, never edited)
  // Moving pins: every pinned mass is at anchor + pin_offset at the end of each substep.
  // anchors: per particle, xyz the start position, w 1 for a pinned mass; empty without pinned_motion.
  std::vector<Vec4<R>> anchors;
  // cloth.attachments (docs/model.md, "Attachments"): per particle, xyz its start position less
  // its collider's origin at t = 0, w the stiffness (0: not attached), and the collider as
  // kind + 4 index (kind 1 sphere, 2 plane, 3 mesh; 0 none). Both empty without attachments.
  std::vector<Vec4<R>> attach;
  std::vector<uint32_t> attach_collider;
  // For an attachment to a skinned collider: the skinned vertex it follows (nearest at t = 0).
  std::vector<uint32_t> attach_vertex;
  // ClothModel::weld when the cloths have seams (params().welds), else empty: self-collision
  // leaves a sewn pair alone.
  std::vector<uint32_t> weld;
  Timeline timeline;
  const layout::StepParamsT<R>& params() const { return *this; }  // the block, as uploaded
  bool has_colliders() const {
    return !control.spheres.empty() || !control.planes.empty() || !control.meshes.empty();
  }
  bool moving_pins() const { return !anchors.empty(); }
  bool has_attachments() const { return !attach.empty(); }
  // Where particle i's collider's origin is at the substep's end (attach_collider[i] != 0); for
  // a skinned collider, where its attached vertex is.
  Vec3<R> attached_origin(size_t i) const {
    const uint32_t code = attach_collider[i], k = code >> 2;
    if ((code & 3u) == 1u) return Vec3<R>(control.spheres[k].origin_radius);
    if ((code & 3u) == 2u) return Vec3<R>(control.planes[k].point);
    const auto& m = control.meshes[k];
    if (m.skin.y > 0) return Vec3<R>(control.skinned[attach_vertex[i]]);  // its vertex, skinned
    return Vec3<R>(m.row0.w, m.row1.w, m.row2.w);
  }
  bool enabled(const Spring& s) const { return materials[s.material].enabled[int(s.type)]; }
  // A spring's rest length and stiffness now: a seam's shrinks as it closes, and takes the lower
  // ks of its two cloths (the same on both ends); any other its cloth's, as built.
  R rest_of(const Spring& s) const {
    return s.type == SpringType::Seam ? shared::seam_rest(R(s.rest), control.seam_shrink) : R(s.rest);
  }
  R stiffness_of(const ClothModel& m, const Spring& s) const {
    if (s.type != SpringType::Seam) return materials[s.material].stiffness(s.type);
    return std::min(materials[m.material[s.i]].ks, materials[m.material[s.j]].ks);
  }
  // Colour c of `m` runs at all: its type is enabled in some cloth (a colour is of one type).
  bool colour_enabled(const ClothModel& m, int c) const {
    for (auto& mat : materials)
      if (mat.enabled[int(m.colour_type(c))]) return true;
    return false;
  }
};

// `reuse`: a hierarchy built for `model` before (a live edit's previous constants). The
// multigrid solver keeps it while the cloths' ks are those it was built with, rather than
// rebuild it (0.4 s at 513²) and re-upload it on every edit of, say, the damping.
template <class R>
Constants<R> make_constants(const Scene& scene, const ClothModel& model,
                            std::shared_ptr<const Hierarchy> reuse = nullptr);

// The control of the substep from t to t + dt (c.control, nothing else of c): the colliders where they are
// at t + dt (when the collision passes run) with their motion over the substep, the pins'
// offset at t + dt (advance moves them there), the gusts' phase at t (when the forces are
// computed). A no-op for a scene in which nothing moves (!c.timeline.moves()).
template <class R> void set_substep_time(Constants<R>& c, double t);

// What changes during a run: positions (w = inverse mass, 0 = pinned), the displacement of
// the last substep (d = x - x_prev, w unused), forces and normals, all vec4 like the GPU
// buffers. The displacement is kept as its own vector rather than recomputed from two
// positions: x - x_prev of two floats near 1 m would round the ~1e-5 m velocity term by ~1 %
// every substep (docs/model.md, "State"). Every change of a position is added to both.
template <class R> struct State {
  std::vector<Vec4<R>> pos, disp, force, normal;
  std::vector<Vec4<R>> wind;        // aerodynamic force per particle (compute_wind_forces); empty without wind
  SpatialHash hash;                 // self-collision scratch, sized once
  std::vector<Vec4<R>> pos_out;     // self-collision Jacobi output
  // Per particle and skinned collider (particle * skin_meshes + MeshCollider::skin.z): the
  // nearest triangle the substep's first collision found (kNoParticle: none within reach),
  // which the later ones reuse (reference_skinning.hpp; BINDING_NEAREST on the GPU). Rebuilt
  // every substep before it is read, so a state without it (saved, uploaded) resumes the same.
  std::vector<uint32_t> nearest;
  // The multigrid solve's scratch (reference_multigrid.cpp), sized on first use. residual: per
  // particle the residual force (w: its mass), then per coarse vertex (at particle count + its
  // global index) the coarse residual (w: the mass it stands for); offset: per particle x - y,
  // its move since the prediction; per coarse vertex the restricted force (w: the mass) and
  // the correction.
  std::vector<Vec4<R>> residual, offset, coarse_rhs, coarse_corr;
  // enforce_stretch_limit's settling passes run so far (a statistic, not part of the state the
  // step reads; StretchControl::state.y on the GPU).
  uint64_t stretch_settling_passes = 0;
};

template <class R> State<R> initial_state(const ClothModel& model);

// After a change of the substep length (frames_per_sec or simulation_steps), the displacement
// per substep scales with it, so the cloth keeps its velocity: d *= dt_new / dt_old.
template <class R> void rescale_displacement(State<R>& s, double dt_ratio) {
  for (auto& d : s.disp) d = Vec4<R>(Vec3<R>(d) * R(dt_ratio), R(0));
}

// The passes, in step order.
// With wind: the aerodynamic force of every particle's triangles, gathered (wind.glsl).
template <class R> void compute_wind_forces(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void accumulate_forces(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void integrate(const ClothModel& m, const Constants<R>& c, State<R>& s);
// Builds the hash (count_cells, scan_cells, fill_cells, sort_cells in spatial_hash.hpp), then
// resolve_self_contacts: the stages the GPU runs as five passes of the same names.
template <class R> void collide_self(const Constants<R>& c, State<R>& s);
template <class R> void resolve_self_contacts(const Constants<R>& c, State<R>& s);  // on s.hash as built
template <class R> void collide_objects(const Constants<R>& c, State<R>& s);
template <class R> void solve_length_constraints(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void compute_normals(const ClothModel& m, State<R>& s);

// Forces then integrate: the CPU twin of the GPU's fused advance pass (which keeps the
// forces in registers; with collision objects fused in it is advance then collide_objects).
// accumulate_forces and integrate on their own are twins of passes the GPU keeps only for
// the pass checks (host/gpu/pass_check.cpp); its step runs advance.
template <class R> void advance(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  accumulate_forces(m, c, s);
  integrate(m, c, s);
}

// One constraint colour (used by the per-pass check that dispatches colours one by one): the
// springs model.colour_start[colour] .. model.colour_start[colour + 1].
template <class R> void solve_length_constraint_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s);

// The fabric solver (docs/model.md): predict moves every free particle by its damped
// displacement, gravity and the wind alone (the springs act in the multigrid solve after it)
// and records where that solve starts (solve_start_offset).
template <class R> void predict(const ClothModel& m, const Constants<R>& c, State<R>& s);
// simulation.stretch_passes as the solvers run it: the scene's count, or for -1 (auto, the
// default), under fabric, kAutoStretchPasses where a cloth's own
// weight would stretch its springs past half its limit (density · |g| · its largest rest extent
// / ks > max_stretch / 2: the classic app's cloths, which rest on their limit; docs/model.md
// step 7), else none; with stretch_passes_max left at -1 those come with settling passes up to
// kAutoStretchPassesMax in all (selfCollision under fabric: 1.1017 with the two alone).
inline constexpr int kAutoStretchPasses = 2;
inline constexpr int kAutoStretchPassesMax = 16;
int stretch_passes_for(const Scene& scene, const ClothModel& model);

// After fabric's sweep: stretch_passes passes of Provot's limit alone over
// every colour (solve_length_constraint_colour): in a sweep a later colour can pull a spring
// limited earlier out again (docs/model.md). With stretch_passes_max above stretch_passes,
// settling passes follow, up to that many in all: the last fixed pass (or one, with none fixed)
// is watched, and each settling pass runs only while the pass before it found a spring longer
// than kStretchSettled times its limit (arm_stretch_pass), so a quiet substep runs none.
template <class R> void enforce_stretch_limit(const ClothModel& m, const Constants<R>& c, State<R>& s);
// A settling pass runs while the pass before it found a spring longer than its limit times
// kStretchSettled = 1 + 2^-kStretchSettledBits: exact in float and double, and handed to the
// watched pass as STRETCH_SETTLED, so both sides compare against the same number.
inline constexpr int kStretchSettledBits = 16;
inline constexpr double kStretchSettled = 1.0 + 1.0 / double(1 << kStretchSettledBits);
// Whether the next watched pass runs: what the pass before it found (`over`), which it clears
// for the next. The CPU twin of compute/arm_stretch_pass.comp.
inline bool arm_stretch_pass(bool& over) { return std::exchange(over, false); }

// The multigrid solver (docs/model.md, "One substep (fabric solver)"), after predict and the
// contacts: compute_residuals (the springs' force on every mass), then a V-cycle over the
// hierarchy's levels (cycle_levels: restrict_residuals level by level down, solve_coarsest,
// then prolong_corrections and smooth_corrections colour by colour up), prolong_to_cloth, and
// relax_vertices colour by colour. solve_multigrid runs them in order. The small levels' part of
// the cycle is cycle_small_levels: one dispatch on the GPU.
inline constexpr int kLevelSweeps = 1;     // Gauss-Seidel sweeps per level on the way up
// A mass this close to a collider's surface (m) is held by it: left out of the coarse problem.
inline constexpr double kContactReach = 1e-3;
// A coarse spring shorter than this times its rest length marks a fold (StepParams::folded_chord):
// the cloth between its ends may have buckled, so the coarse vertex is fixed. 0.99 (the removed
// multigrid solver's, still folded_chord_stiff: change 5) held back a swinging cloth (its free
// edge's chords shorten by 1-3 % as it swings) and let the 257² hang tear at its pins; 1 (any
// slack chord) also fixes the slightly compressed lower cloth and slows its hanging (docs/solvers.md).
inline constexpr double kFoldedChordMultigrid = 0.99;
inline constexpr double kFoldedChordFabric = 0.95;
// fabric's adaptive start takes its whole share up to a mass's rho = ks dt^2 / m of this, less
// above (adaptive_share, folded_chord_at). The 513² hang (rho 1,200) tore with the whole share,
// flag512 (rho 300) on landing with the bound at 300; at 250 a small disc slid off (docs/solvers.md).
inline constexpr double kAdaptiveStartRho = 200.0;
// A cloth with a material starts its solve where multigrid did (its share 0, adaptive_share of
// a stiffness this high): its bending, which the coarse levels do not carry, leaves a share of
// the fall in the start unsolved, and the cantilever (tests/test_materials.cpp) then swings
// without settling (docs/materials.md).
inline constexpr double kMaterialStartStiffness = 1e30;
inline constexpr int kCoarsestSweeps = 4;  // on the coarsest level (solve_coarsest)
// A level of at most this many vertices, and every level below it, is small: the GPU runs
// their part of the cycle in one workgroup (cycle_small_levels), where a dispatch and a
// barrier per colour would cost more than the levels' work (on a 256² cloth 19 of the 43
// dispatches of a substep went to its four levels of 1,027 vertices and fewer).
inline constexpr uint32_t kSmallLevelVertices = 2048;
// The first small level of `h` (its coarsest level is always one); 0 for none.
int first_small_level(const Hierarchy& h);
template <class R> void compute_residuals(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void restrict_residuals(const Constants<R>& c, int level, State<R>& s);
template <class R> void smooth_corrections(const Constants<R>& c, int level, int colour, State<R>& s);
// `sweeps` Gauss-Seidel sweeps of one level, colour by colour (smooth_corrections).
template <class R> void smooth_level(const Constants<R>& c, int level, int sweeps, State<R>& s);
template <class R> void solve_coarsest(const Constants<R>& c, State<R>& s);
// The small levels' part of the cycle, in cycle_levels' order: restrict_residuals down from the
// first small level, solve_coarsest, then prolong_corrections and smooth_level up to it.
template <class R> void cycle_small_levels(const Constants<R>& c, State<R>& s);
template <class R> void prolong_corrections(const Constants<R>& c, int level, State<R>& s);
template <class R> void prolong_to_cloth(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void relax_vertices(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s);
template <class R> void cycle_levels(const Constants<R>& c, State<R>& s);
template <class R> void solve_multigrid(const ClothModel& m, const Constants<R>& c, State<R>& s);

// The speed clamp's last word (simulation.max_speed): after the constraints and the contacts,
// a free mass whose substep moved it further than max_move goes back along its move to
// max_move from where it started (a fast collider cannot fling it faster either).
template <class R> void limit_speed(const ClothModel& m, const Constants<R>& c, State<R>& s);

// One substep: the pass list of docs/design.md §1, or of docs/model.md for fabric; with a profile,
// each pass timed (simulate --profile).
template <class R> void step(const ClothModel& m, const Constants<R>& c, State<R>& s, PassProfile* profile = nullptr) {
  auto pass = [profile](std::string_view name, auto&& f) { profiled(profile, name, f); };
  if (c.wind_enabled) pass("compute_wind_forces", [&] { compute_wind_forces(m, c, s); });  // advance or predict add them
  if (c.multigrid) {
    pass("predict", [&] { predict(m, c, s); });
    if (c.self_collision) pass("collide_self", [&] { collide_self(c, s); });
    pass("collide_objects", [&] { collide_objects(c, s); });
    pass("solve_multigrid", [&] { solve_multigrid(m, c, s); });
    pass("enforce_stretch_limit", [&] { enforce_stretch_limit(m, c, s); });  // a later colour can pull a limited spring out
  } else {
    pass("advance", [&] { advance(m, c, s); });
    if (c.self_collision) pass("collide_self", [&] { collide_self(c, s); });
    pass("collide_objects", [&] { collide_objects(c, s); });
    pass("solve_length_constraints", [&] { solve_length_constraints(m, c, s); });
  }
  if (c.max_move > R(0)) pass("limit_speed", [&] { limit_speed(m, c, s); });
}

}  // namespace clothsim

// The one source of truth for the GPU data layout, compiled by both C++ and GLSL.
// std430 for storage buffers, std140 for the parameter block. Every member of a storage
// buffer struct is a vec4/uvec4 so the two rules and the C++ compiler all agree (a vec3[]
// would have a 16-byte stride in GLSL and 12 in C++); the parameter block is named scalars.
// tests/test_gpu_layout.cpp asks GL for the real offsets and strides and compares them with
// sizeof/offsetof here. Constants and functions that both languages need beyond the layout
// (the hash) live in spatial_hash.glsl. The cloth model's lists (host/core/cloth/cloth.hpp) are read
// through texel views of the layouts below.
#ifndef CLOTHSIM_LAYOUT_GLSL
#define CLOTHSIM_LAYOUT_GLSL

#ifdef __cplusplus
#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
namespace layout {
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
using uvec2 = glm::uvec2;
using uint = uint32_t;
#define STRUCT_ALIGN16 struct alignas(16)
#else
#define STRUCT_ALIGN16 struct
#endif
// The structs the CPU reference reads too (the colliders, StepParams) are declared once in a
// dialect of both languages: in C++ a template on the scalar REAL, NameT<REAL> (the reference
// runs in float and double; the GPU uploads the float one's bytes as they are, and only its
// layout is checked), with `Name` the float one; in GLSL the plain struct `Name` of floats.
#ifdef __cplusplus
#define VEC3 glm::vec<3, REAL>
#define VEC4 glm::vec<4, REAL>
#define UINT uint32_t
#define SCALAR_STRUCT(Name) template <class REAL> struct alignas(16) Name##T
#else
#define REAL float
#define VEC3 vec3
#define VEC4 vec4
#define UINT uint
#define SCALAR_STRUCT(Name) struct Name
#endif

// Shader-storage buffer bindings of the simulation (one per per-particle stream). The
// simulator binds them once per step; nothing else uses these points, so they stay put while
// the renderer, the scan and the divergence guard bind their own.
#define BINDING_POSITIONS 0   // vec4: xyz position, w inverse mass (0 = pinned)
#define BINDING_DISPLACEMENT 1    // vec4: xyz x - x_prev (the substep's move so far), w predict's clearance bound (predict.comp; 0 in a State)
#define BINDING_FORCES 2      // vec4: xyz force of this substep
#define BINDING_NORMALS 3     // vec4: xyz unit vertex normal
#define BINDING_SPRINGS 4     // SpringTexel per spring, sorted by colour (ClothModel::springs)
#define BINDING_MATERIALS 24  // MaterialTexels per cloth (the passes read them through TEXTURE_MATERIALS)
#define BINDING_SPHERES 5     // SphereCollider[]
#define BINDING_PLANES 6      // PlaneCollider[]
#define BINDING_POSITIONS_OUT 7  // vec4: Jacobi output of self-collision
#define BINDING_CELL_COUNT 8     // uint per hash bucket
#define BINDING_CELL_START 9     // uint per hash bucket (+1 sentinel)
#define BINDING_CELL_ENTRIES 10  // uint particle id, in cell order
#define BINDING_SORTED_POSITIONS 11  // vec4: positions in cell order (entries order), for resolve_self_contacts
// The prefix scan's own bindings (host/gpu/prefix_scan.cpp).
#define BINDING_SCAN_SUMS 12     // uint per scan block (multi-level prefix sum)
#define BINDING_SCAN_DATA 13     // uint array being scanned in place
// The divergence guard's own bindings (host/gpu/gpu_divergence.cpp).
#define BINDING_CHECKED_POSITIONS 14  // vec4: the positions of the frame being checked
#define BINDING_FRAME_BOUNDS 15  // FrameBounds of one frame (check_divergence)
#define BINDING_LAST_GOOD 16     // LastGoodHeader, then vec4 per particle: newest frame that passed (keep_last_good)
// The renderer's own bindings (shaders/vertex_pull.glsl): the cloth's buffers, or a collider mesh's.
#define BINDING_DRAW_POSITIONS 17  // vec4: xyz position of each vertex drawn
#define BINDING_DRAW_NORMALS 18    // vec4: xyz unit normal of each vertex drawn
#define BINDING_DRAW_EXTRAS 19     // MeshVertex extras (uv, tangent) of collider meshes
#define BINDING_DRAW_SHADOW 20     // ShadowFrame of this frame (shaders/fit_shadow_frustum.comp)
// Moving cloth and air (compute/wind.glsl, compute/pinned_motion.glsl); one dummy element each
// when the scene has no wind / no pinned_motion. 21 is the layout test's probe.
#define BINDING_WIND_FORCES 22  // vec4: xyz aerodynamic force of this substep (compute_wind_forces)
#define BINDING_ANCHORS 23      // vec4: xyz start position, w 1 for a pinned mass (pinned_motion)
#define BINDING_MESHES 26  // MeshCollider[] (the passes read them through TEXTURE_MESHES)
#define BINDING_SDF 27     // vec4 per field node (host/gpu/sdf_texels.hpp), every mesh collider's field in turn
// The multigrid solver's scratch (docs/model.md, host/core/cloth/hierarchy.hpp), vec4 each.
#define BINDING_MG_RESIDUALS 28  // per particle its residual force (w its mass), then per coarse vertex its coarse residual (w the mass it stands for)
#define BINDING_MG_OFFSET 29     // per particle: xyz its move since the prediction (x - y)
#define BINDING_MG_RHS 30        // per coarse vertex: xyz the restricted force, w the mass it stands for
#define BINDING_MG_CORR 31       // per coarse vertex: xyz its correction
// enforce_stretch_limit's settling passes (docs/model.md, xpbd step 6): a StretchControl, then
// per colour a StretchDispatch (glDispatchComputeIndirect reads it; arm_stretch_pass writes it).
// It shares the scan's point (BINDING_SCAN_SUMS): each binds its own buffer there before use
// (prefix_scan.cpp, gpu_stretch_limit.cpp), and a point above 31 is more than some drivers have.
#define BINDING_STRETCH_CONTROL BINDING_SCAN_SUMS
// The contact list (compute/contact_list.glsl): a ContactListHeader, then a uint per listed
// mass; on the scan's data point, which the scan binds again before its next use.
#define BINDING_CONTACT_LIST BINDING_SCAN_DATA
// Skinned mesh colliders (docs/model.md, "Skinned and animated colliders"): skin_colliders writes the
// skinned vertices, and fit_collider_boxes the boxes (TEXTURE_SKINNED says where), through the scan's
// sums point, binding its buffer there before each use as the scan and the settling passes do.
#define BINDING_SKINNED BINDING_SCAN_SUMS
// Per particle and skinned collider (particle * skin_meshes + MeshCollider::skin.z), uint: the
// nearest triangle of its last search, which the substep's later collisions reuse; then the far
// records and the summed moves (compute/nearest.glsl says how they lie). Shares the layout
// test's probe point, which binds its own buffer there.
#define BINDING_NEAREST 21
// Texture units of the read-only texel views (GL_TEXTURE_BUFFER) of the simulation's buffers,
// through which the hot passes read (compute/particle_views.glsl says why). Above the units
// the renderer uses (0-2: fabric, height map, sky), so drawing a frame leaves them bound.
#define TEXTURE_POSITIONS 8          // RGBA32F, one texel per particle
#define TEXTURE_DISPLACEMENT 9           // RGBA32F, one texel per particle
#define TEXTURE_SPRINGS 10           // RGBA32UI, one SpringTexel per spring, sorted by colour
#define TEXTURE_SPHERES 11           // RGBA32F, SPHERE_TEXELS per SphereCollider
#define TEXTURE_PLANES 12            // RGBA32F, PLANE_TEXELS per PlaneCollider
#define TEXTURE_CELL_START 13        // R32UI, one texel per hash bucket (+1 sentinel)
#define TEXTURE_SORTED_POSITIONS 14  // RGBA32F, one texel per hash entry
// The rest of the cloth model (ClothModel in host/core/cloth/cloth.hpp), static over a run.
#define TEXTURE_GATHER_START 16      // R32UI, per particle + 1: its first gather entry; with a material, then its first membrane and hinge entries likewise
#define TEXTURE_GATHER 17            // RGBA32UI, per gather entry: x the other end | type << 30, y the rest length's bits; then 2 per membrane and hinge entry (gpu_state.cpp)
#define TEXTURE_PARTICLES 18         // RGBA32F, per particle: x mass (kg), y its cloth's material index, z its attachment's collider (kind + 4 index, 0 none), w the skinned vertex it follows (a skinned collider's)
#define TEXTURE_MATERIALS 19         // RGBA32F, MATERIAL_TEXELS per cloth (MaterialTexels)
#define TEXTURE_CORNER_START 20      // R32UI, per particle + 1: its first entry in the corner list
#define TEXTURE_CORNER_TRIANGLES 21  // R32UI, per corner entry: a triangle around the particle (ascending)
#define TEXTURE_TRIANGLES 22         // RGBA32UI, per triangle: xyz its corners
#define TEXTURE_REST_POSITIONS 23    // RGBA32F, per particle: xyz its rest position (bounded contact), w its weld (seams); 1 texel without either
#define TEXTURE_MESHES 25            // RGBA32F, MESH_TEXELS per MeshCollider
#define TEXTURE_SDF 26               // RGBA32F, per field node its value and its +x, +y, +x+y neighbours' (BINDING_SDF)
// The same buffer as TEXTURE_MESHES as RGBA32I, for MeshCollider's integers (dims): read through
// the float view they would be denormal floats, which a driver may flush to zero (AMD and Intel do).
#define TEXTURE_MESHES_INT 35        // RGBA32I, MESH_TEXELS per MeshCollider
// cloth.attachments (Constants::attach): per particle xyz its start position less its collider's
// start origin, w the stiffness (0: none); the collider's code is the particle texel's z.
#define TEXTURE_ATTACHMENTS 36       // RGBA32F, per particle (1 texel without attachments)
// Skinned mesh colliders (one texel each without): the skinned vertices and the clusters' boxes
// (BINDING_SKINNED), every skinned collider's vertices, triangles and clusters in turn.
#define TEXTURE_SKINNED 37           // RGBA32F: per vertex now, then at the substep's start, then in the bind pose; then per cluster, then per group, its box's lo and hi
#define TEXTURE_SKIN_INDICES 38      // RGBA32UI: per vertex its bones; per triangle its vertices; per cluster x its first triangle, y its count; per group x its first cluster, y its count
#define TEXTURE_SKIN_WEIGHTS 39      // RGBA32F, per vertex: its bones' weights
#define TEXTURE_SKIN_PALETTE 40      // RGBA32F, per palette entry 3 rows (xyz the linear part, w the translation): at the substep's start, then at its end
// The multigrid hierarchy (Hierarchy in host/core/cloth/hierarchy.hpp), static over a run, and the views of its scratch.
#define TEXTURE_MG_VERTICES 27       // RGBA32UI, per coarse vertex + 1: x its particle, y its first child, z its first parent, w its first spring (entries of TEXTURE_MG_LISTS)
#define TEXTURE_MG_LISTS 28          // RGBA32UI, MultigridEntry: the children, then the parents, the springs, the particles' parents
#define TEXTURE_MG_FINE 29           // R32UI, per particle + 1: its first parent (an entry of TEXTURE_MG_LISTS); then per particle its fine colour
#define TEXTURE_MG_ORDER 30          // R32UI: the particles by colour, then every level's coarse vertices by colour
#define TEXTURE_MG_CORR 31           // RGBA32F, per coarse vertex: BINDING_MG_CORR, read by its neighbours
#define TEXTURE_MG_OFFSET 32         // RGBA32F, per particle: BINDING_MG_OFFSET, read by the passes after predict
#define TEXTURE_MG_RESIDUALS 33      // RGBA32F, per particle then coarse vertex: BINDING_MG_RESIDUALS, read by the next coarser level
#define TEXTURE_MG_RHS 34            // RGBA32F, per coarse vertex: BINDING_MG_RHS, read by the smoothing and the prolongation
// RGBA32F texels per struct in the views above: member m of element k is texel
// k * STRUCT_TEXELS + m (tests/test_gpu_layout.cpp checks these against the std430 strides).
#define MATERIAL_TEXELS 3
#define SPHERE_TEXELS 3
#define PLANE_TEXELS 3
#define MESH_TEXELS 9
// Uniform block bindings: the parameter block (uploaded at construction and on live edits) and
// the substep's control (uploaded every substep when something moves).
#define BINDING_STEP_PARAMS 0
#define BINDING_SUBSTEP_CONTROL 1

// Threads per workgroup for every per-particle pass (a 1-D dispatch over the particle index).
#ifndef WORKGROUP_SIZE
#define WORKGROUP_SIZE 128
#endif
// Elements one invocation of scan_cells sums serially (the block of the multi-level scan).
#define SCAN_CHUNK 32
// One spring of the model: x, y its ends, z the rest length's bits, w SpringType | material << 2 (3: a seam).
struct SpringTexel {
  uvec4 ends_rest_code;
};

// One entry of the multigrid hierarchy's lists: x an index (a child's residual, a parent, a
// spring's other end), y a weight's float bits (a child's, a parent's) or a spring's rest
// length's, z a spring's stiffness's bits, w a spring's other end's particle (its position,
// without a second fetch for the coarse vertex).
struct MultigridEntry {
  uvec4 index_weight;
};

// One cloth's material (MaterialC in host/core/reference/reference.hpp).
struct MaterialTexels {
  vec4 stiffness;  // ks, ks_bending, the start's (MaterialC::start_ks) (N/m), w unused
  vec4 keep;       // x 1 - damping / 100; y, z, w 1 where structural, shearing, bending springs are enabled
  vec4 moduli;     // a material's C11, C22 (N/m), compression ratio, G (N/m; shared/membrane.glsl), else 0
};

// `motion`: the collider's displacement over this substep (keyframed motion, set by the host
// every substep); exactly 0 for a static collider, which then takes the classic formulas.
// keep.x multiplies the tangential motion kept in a contact (the CS184 blend), keep.y is
// xpbd's Coulomb mu. Origin, point and motion belong to the substep (Control in
// host/core/reference/reference.hpp); the rest is fixed over a run.
SCALAR_STRUCT(SphereCollider) {
  VEC4 origin_radius;  // xyz origin (at the substep's end), w radius
  VEC4 keep;           // x = 1 - friction, y = friction (xpbd's Coulomb mu)
  VEC4 motion;         // xyz m over this substep
};

// point.w, the front: the side of the plane the cloth starts on (its rest centre's side, +1
// when on it); a mass is in contact whenever it is not in front, however it got behind (with
// xpbd's Coulomb friction also when within the surface offset in front: docs/model.md).
SCALAR_STRUCT(PlaneCollider) {
  VEC4 point;   // xyz a point on the plane (at the substep's end), w its front: +1 or -1, the cloth's side
  VEC4 normal;  // xyz unit normal, w = 1 - friction
  VEC4 motion;  // xyz m over this substep, w = friction (xpbd's Coulomb mu)
};

// A mesh collider through its signed distance field (host/core/colliders/sdf.hpp): a mass at x
// is at local = rows (x - origin) in its field's frame (rows: the rotation's transpose); node
// (0, 0, 0) of the field is at grid_min, its nodes are the texels of TEXTURE_SDF (on the CPU
// Constants::sdf) from dims.w on, x fastest (each with its +x, +y, +x+y neighbours). A mass
// closer than `thickness` to the surface (or inside) is pushed out along the field's gradient.
// closed: the field is signed (a closed mesh); else unsigned, the collider a shell. crossing:
// half the thickness, how near two path samples straddling a shell pass (passed_through_mesh).
SCALAR_STRUCT(MeshCollider) {
  VEC4 row0;       // xyz the first row of the rotation's transpose, w origin.x (at the substep's end)
  VEC4 row1;       // xyz the second row, w origin.y
  VEC4 row2;       // xyz the third row, w origin.z
  VEC4 grid;       // xyz grid_min, w 1 / node spacing
  ivec4 dims;      // xyz nodes along x, y, z, w the offset of node (0, 0, 0) (read through TEXTURE_MESHES_INT)
  VEC4 motion;     // xyz m over this substep, w = 1 - friction
  VEC4 material;   // x friction (xpbd's Coulomb mu), y thickness (m), z crossing, w 1 closed, 0 open
  VEC4 bound;      // x the field's slope bound in the world (sdf_slopes; the GPU's contact list), yzw unused
  ivec4 skin;      // a skinned collider: x its first super-group of groups, y its super-groups (0: rigid), z its index among the skinned ones, w unused (TEXTURE_MESHES_INT)
};

// Per-vertex extras of a drawn mesh: a collider's uv and tangent; the cloth's uv, and in uv.zw the particles
// whose difference is its tangent (ClothModel::tangent_ends; the cloth's tangent moves with it).
struct MeshVertex {
  vec4 uv;       // xy texture coordinates
  vec4 tangent;  // xyz unit tangent along +u
};

// The contact list's header: glDispatchComputeIndirect reads x, y, z as collide_objects'
// workgroups; w counts the masses listed. Cleared to (0, 1, 1, 0) before each appending pass.
struct ContactListHeader {
  uvec4 dispatch_count;
};

// The key light's shadow projection of one drawn frame, fitted on the GPU to the bounds of the
// cloth (read in place) and the colliders by shaders/fit_shadow_frustum.comp, then read by the
// shadow pass and every lit shader (shaders/shadow.glsl). A perspective from the light's
// position onto the casters' bounding sphere: the map covers what casts and nothing more.
struct ShadowFrame {
  vec4 view_projection[4];  // columns of the world -> light clip matrix
  vec4 light;               // xyz the light's position, w the radius of its disc (m): the penumbrae's size
  vec4 range;               // x near, y far (m along the light's axis), z tan of the half angle, w 1 / map texels per side
};

// Everything a pass needs that is constant over a substep: the CPU reference's own (Constants<R>
// in host/core/reference/reference.hpp is built on StepParamsT<R>), uploaded from
// Constants<float> as it is, so both sides see identical floats. One named scalar per value
// (std140 packs consecutive scalars as C++ does, and the vec3 first leaves exactly the 4 bytes
// the scalar after it takes), declared once through STEP_PARAMS_FIELDS so that
// tests/test_gpu_layout.cpp checks every field's offset and value, a field added later included.
#define STEP_PARAMS_FIELDS(F)                                                               \
  F(VEC3, gravity)             /* m/s^2 */                                                 \
  F(REAL, dt2)                 /* s^2, the substep squared */                              \
  F(VEC3, wind_velocity)       /* m/s, of the air (docs/model.md, "Wind") */                \
  F(REAL, wind_drag)           /* -rho C_d / 12 */                                         \
  F(VEC3, gust_velocity)       /* m/s, strength * wind_velocity */                         \
  F(REAL, wind_lift)           /* -rho C_l / 12 */                                         \
  F(VEC3, wind_direction)      /* unit wind_velocity (gusts travel along it) */            \
  F(REAL, wind_inv_3dt)        /* 1/s, 1 / (3 dt) */                                       \
  F(REAL, stretch_limit)       /* 1 + max_stretch */                                       \
  F(REAL, contact_distance)    /* m, 2 thickness: self-collision keeps masses this far */  \
  F(REAL, inv_cell)            /* 1/m, 1 / the hash cell edge (edge = contact_distance) */ \
  F(REAL, steps)               /* simulation_steps, as a float */                          \
  F(REAL, tether_limit)        /* xpbd: 1 + tether_stretch */                              \
  F(UINT, count)               /* particles */                                             \
  F(UINT, table_size)          /* hash buckets, a power of two */                          \
  F(UINT, sphere_count)        /* SphereCollider entries in use */                         \
  F(UINT, plane_count)         /* PlaneCollider entries in use */                          \
  F(REAL, gust_inv_length3)    /* 1/m, 1 / (3 gust length) */                              \
  F(UINT, wind_enabled)        /* 1 = compute_wind_forces runs and advance adds its force */ \
  F(UINT, gust_enabled)        /* 1 = the wind has gusts */                                \
  F(UINT, pins_moving)         /* 1 = pinned masses follow pinned_motion */                \
  F(UINT, bounded_contact)     /* 1 = xpbd's self-contact (docs/model.md) */               \
  F(REAL, max_step)            /* m, predict's displacement limit per substep (0: none) */ \
  F(UINT, coulomb_friction)    /* 1 = contacts take Coulomb friction (xpbd), 0 the CS184 blend */ \
  F(UINT, mesh_count)          /* MeshCollider entries in use */                         \
  F(REAL, inv_dt2)             /* 1/s^2, 1 / dt^2: a mass's inertia per kg (multigrid) */   \
  F(UINT, multigrid)           /* 1 = the multigrid solve (multigrid, fabric) */            \
  F(REAL, adaptive_rho)        /* fabric: > 0, the multigrid solve starts where the last substep's move says, scaled above this ks dt^2 / m */ \
  F(UINT, sweep_friction)      /* 1 = fabric: the push-out after the multigrid sweep takes Coulomb friction */ \
  F(REAL, max_move)            /* m, simulation.max_speed * dt: integration's move limit per substep (0: none) */ \
  F(UINT, skin_vertices)       /* every skinned collider's vertices (TEXTURE_SKINNED's sections) */ \
  F(UINT, skin_triangles)      /* and triangles */                                          \
  F(UINT, skin_clusters)       /* and clusters of triangles */                              \
  F(UINT, skin_groups)         /* and groups of clusters */                                 \
  F(UINT, skin_supers)         /* and super-groups of groups */                             \
  F(UINT, skin_palette)        /* and palette entries (bones) */                            \
  F(UINT, skin_meshes)         /* skinned mesh colliders (BINDING_NEAREST's slots per particle) */ \
  F(UINT, welds)               /* 1 = seams: TEXTURE_REST_POSITIONS' w is each particle's weld (ClothModel::weld) */ \
  F(REAL, folded_chord)        /* multigrid, fabric: a coarse spring shorter than this share of its rest length is in a fold */ \
  F(REAL, folded_chord_stiff)  /* fabric: the threshold folded_chord moves to as a mass's adaptive share drops (multigrid's) */
#define STEP_PARAMS_DECLARE(type, name) type name;
// std140 rounds the block's size up to 16 bytes; alignas makes sizeof agree (for REAL = float:
// StepParamsT<double> is the double reference's, never uploaded).
SCALAR_STRUCT(StepParams) { STEP_PARAMS_FIELDS(STEP_PARAMS_DECLARE) };

// The substep's control (issue 42, item 4): the scalars of the per-substep control that the
// passes read from a uniform block (Control<R> in host/core/reference/reference.hpp is built on
// SubstepControlT<R>, with the colliders' arrays, which have buffers of their own). Set for the
// substep's time by set_substep_time and uploaded on its own, every substep when something moves;
// its own field list so that tests/test_gpu_layout.cpp checks it as it does StepParams.
#define SUBSTEP_CONTROL_FIELDS(F)                                                           \
  F(VEC3, pin_offset)          /* m, pinned_motion at the substep's end */                 \
  F(REAL, gust_phase)          /* fract(t / period) at the substep's start */              \
  F(REAL, seam_shrink)         /* m, sewing_speed * t at the substep's end: what every seam's rest length has lost */
SCALAR_STRUCT(SubstepControl) { SUBSTEP_CONTROL_FIELDS(STEP_PARAMS_DECLARE) };

// The divergence guard's reduction of one frame. Coordinates are stored as ordered bits
// (compute/divergence.glsl): uints whose unsigned order is the float order, so that
// atomicMin/atomicMax reduce them.
struct FrameBounds {
  uvec4 lo;  // xyz smallest finite coordinate (ordered bits), w 1 if any coordinate is NaN/Inf
  uvec4 hi;  // xyz largest finite coordinate (ordered bits), w unused
};

// The settling passes' state (BINDING_STRETCH_CONTROL): x 1 once a watched pass found a spring
// over its limit by more than kStretchSettled since the last arm_stretch_pass, y the settling
// passes run since the buffer was made (State::stretch_settling_passes on the CPU), zw unused.
struct StretchControl {
  uvec4 state;
};

// One colour's dispatch of a watched pass: xyz the workgroups glDispatchComputeIndirect reads
// (x 0 when arm_stretch_pass skips the pass), w the colour's workgroups when it runs.
struct StretchDispatch {
  uvec4 groups;
};

// In front of the kept positions of keep_last_good.
struct LastGoodHeader {
  uvec4 state;  // x 1 once a frame has failed (no later frame is kept), y the frame kept, zw unused
};

#ifdef __cplusplus
using SphereCollider = SphereColliderT<float>;
using PlaneCollider = PlaneColliderT<float>;
using MeshCollider = MeshColliderT<float>;
using StepParams = StepParamsT<float>;
using SubstepControl = SubstepControlT<float>;
static_assert(sizeof(SubstepControl) == 32, "SubstepControl is two vec4s");
static_assert(sizeof(MaterialTexels) == MATERIAL_TEXELS * sizeof(vec4), "MaterialTexels texels");
static_assert(sizeof(SphereCollider) == SPHERE_TEXELS * sizeof(vec4), "SphereCollider texels");
static_assert(sizeof(PlaneCollider) == PLANE_TEXELS * sizeof(vec4), "PlaneCollider texels");
static_assert(sizeof(MeshCollider) == MESH_TEXELS * sizeof(vec4), "MeshCollider texels");
static_assert(sizeof(ShadowFrame) == 6 * sizeof(vec4), "ShadowFrame is six vec4");
static_assert(sizeof(StretchDispatch) == 16, "an indirect dispatch per 16 bytes");
}  // namespace layout
#endif
#endif

// Scene description: what a scene JSON file says, validated (docs/design.md §4).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

namespace clothsim {

enum class Orientation { Horizontal = 0, Vertical = 1 };
// classic: the CS184 mass-spring model (explicit springs, Verlet, Provot); fabric: implicit
// Euler solved by a multigrid V-cycle and a vertex sweep (docs/solvers.md).
enum class Solver { Classic = 0, Fabric = 1 };

// One key of a keyframed motion: at `time` (simulated seconds) the value is `value`.
struct Keyframe {
  double time = 0;
  glm::dvec3 value{0.0};

  bool operator==(const Keyframe&) const = default;
};
// Times strictly ascending (the loader checks it), at least one key.
using Keyframes = std::vector<Keyframe>;

// `"motion": {"keyframes": [[t, [x, y, z]], ...]}`: linear between keys, held before the first
// and after the last (motion.hpp evaluates it).
struct MotionParams {
  Keyframes keyframes;

  bool operator==(const MotionParams&) const = default;
};

// `cloth.pinned_box`: every vertex of a mesh cloth inside [min, max] (inclusive) is pinned.
struct BoxParams {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};

  bool contains(const glm::dvec3& p) const {  // inclusive
    return glm::all(glm::greaterThanEqual(p, min)) && glm::all(glm::lessThanEqual(p, max));
  }
  bool operator==(const BoxParams&) const = default;
};

// `cloth.attachments[k]` (docs/model.md, "Attachments"): cloth vertices tied to a collider by a
// zero-length spring each, to where the vertex started plus the collider's move since t = 0, so
// they follow the collider (a cape at the shoulders, a waistband). Either `vertices` (0-based:
// a mesh cloth's in its file's order, a grid's row-major, y * num_width_points + x, the order of
// the exported OBJ) or `box` (every vertex whose start position is inside) says which, or both.
struct AttachmentParams {
  std::string collider;                   // "sphere", "sphere[1]", "plane[0]", "mesh", "mesh[2]"
  std::vector<int> vertices;
  std::optional<BoxParams> box;
  double stiffness = 1000;                // N/m per vertex

  bool operator==(const AttachmentParams&) const = default;
};

// `cloth.seams[k]` (docs/model.md, "Sewing"): cloth vertices sewn to others of this cloth or of
// another cloth of the array. Each side picks its vertices by `vertices` (0-based, as in
// AttachmentParams), by a grid's `edge` ("x_min", "x_max", "y_min", "y_max": a row or column of
// grid indices, in ascending order) or by `box` (every vertex whose start position is inside,
// ordered along the box's longest side); the k-th vertex of one side is sewn to the k-th of the
// other. The seam's springs start at the pair's distance and shrink at simulation.sewing_speed
// to zero length, then hold the pair as one point.
struct SeamParams {
  std::vector<int> vertices;
  std::string edge;
  std::optional<BoxParams> box;
  int to_cloth = -1;  // the other side's cloth (0-based, in the array); -1: this one
  std::vector<int> to_vertices;
  std::string to_edge;
  std::optional<BoxParams> to_box;

  bool operator==(const SeamParams&) const = default;
};

// How a mesh cloth's mass (density x area) is spread over its vertices: `area`, each vertex a
// third of the area of each triangle around it (a quarter of each quad); `uniform`, the total
// shared equally, as the CS184 grid does (docs/model.md, "Mesh cloth").
enum class MassLumping { Area = 0, Uniform = 1 };

// `cloth.material` (docs/materials.md): a fabric in physical units for the fabric solver, a
// preset's name or these keys. `preset` fills every value the scene leaves at 0 (the loader
// resolves it, so after loading every value is set); `stretch` and `bending` are [warp, weft]
// (warp along the grid's width or the mesh's texture u), a single number meaning both.
struct MaterialParams {
  std::string preset;
  double density = 0;                 // kg/m^2
  std::array<double, 2> stretch{};    // N/m, uniaxial: force per width over strain
  double shear = 0;                   // N/m, in-plane shear modulus
  std::array<double, 2> bending{};    // N·m, bending rigidity
  double compression = 0;             // a shortened direction's stiffness over its stretch, (0, 1]

  bool operator==(const MaterialParams&) const = default;
};
// The cloth keys a material replaces: the loader refuses them beside one (which should hold
// would be a guess) and scene_to_json leaves them out of a cloth that has one.
inline constexpr std::string_view kKeysMaterialReplaces[] = {"density", "ks", "enable_structural", "enable_shearing",
                                                             "enable_bending"};

// Field names are the JSON keys (one name end to end: file, code, GUI).
struct ClothParams {
  double width = 1.0;
  double height = 1.0;
  int num_width_points = 50;
  int num_height_points = 50;
  double thickness = 0.0095;
  Orientation orientation = Orientation::Horizontal;
  std::vector<std::array<int, 2>> pinned;  // [x, y] grid indices
  bool enable_structural = true;
  bool enable_shearing = true;
  bool enable_bending = true;
  double damping = 0.2;   // percent
  double density = 150;   // kg/m^2
  double ks = 5000;       // N/m
  std::optional<MotionParams> pinned_motion;  // keys are offsets [dx, dy, dz] of every pinned mass
  std::vector<AttachmentParams> attachments;   // vertices that follow a collider
  std::vector<SeamParams> seams;               // vertices sewn to others
  // A cloth from a mesh file instead of the grid (docs/model.md, "Mesh cloth"). `mesh` is the
  // path as the scene writes it, relative to the scene file; mesh_path is it resolved (set by
  // the loader; empty: the CS184 grid of num_width_points x num_height_points).
  std::string mesh;
  std::filesystem::path mesh_path;
  std::vector<int> pinned_vertices;     // 0-based, in the file's vertex order
  std::optional<BoxParams> pinned_box;  // every vertex inside is pinned
  // Placement of the mesh: x' = R(axis, degrees) (scale x) + offset.
  double scale = 1;
  glm::dvec3 offset{0.0};
  glm::dvec3 rotation_axis{0, 1, 0};
  double rotation_degrees = 0;
  MassLumping mass_lumping = MassLumping::Area;
  // A fabric in physical units (fabric solver only): replaces density, ks and the springs.
  std::optional<MaterialParams> material;

  bool is_mesh() const { return !mesh.empty(); }
  // Mass per area (kg/m^2): the material's, else `density`.
  double areal_density() const { return material ? material->density : density; }
  // The spring constant the solver's estimates use (the coarse springs, the fold threshold, the
  // start): ks, or for a material the mean stretch stiffness over 1.4 (a CS184 grid of springs
  // ks resists a uniform stretch as 1.4 ks: docs/model.md).
  double spring_ks() const { return material ? 0.5 * (material->stretch[0] + material->stretch[1]) / 1.4 : ks; }
  bool operator==(const ClothParams&) const = default;
};

struct SphereParams {
  glm::dvec3 origin{0.0};
  double radius = 0;
  double friction = 0;
  std::optional<MotionParams> motion;  // keys are origins; replaces `origin` while present

  bool operator==(const SphereParams&) const = default;
};

struct PlaneParams {
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0, 1, 0};  // unit length after loading
  double friction = 0;
  std::optional<MotionParams> motion;  // keys are points on the plane; replaces `point` while present

  bool operator==(const PlaneParams&) const = default;
};

// A triangle mesh as a collider (docs/model.md, "Mesh colliders"): the file's surface, scaled,
// rotated about rotation_axis, then placed at `origin` (keyframed by `motion`), collided with
// through its signed distance field of node spacing voxel_size.
struct MeshColliderParams {
  std::string file;                 // as the scene writes it, relative to the scene file
  std::filesystem::path file_path;  // resolved by the loader
  double scale = 1;
  glm::dvec3 origin{0.0};
  glm::dvec3 rotation_axis{0, 1, 0};  // unit length after loading
  double rotation_degrees = 0;
  double friction = 0;
  std::optional<MotionParams> motion;  // keys are origins; replaces `origin` while present
  double voxel_size = 0;   // m; 0: the mesh's longest extent / 128 (sdf.hpp)
  double thickness = 0.002;  // m: masses are kept this far outside the surface
  // A skinned, animated collider (colliders/skin.hpp): the name or index of one of the file's
  // animations ("": a rigid collider), played at time_scale, looping or held at its end.
  std::string animation;
  double time_scale = 1;
  bool loop = true;
  // Or the vertices from a point cache: a PC2 file, or a folder of OBJ files (one a frame) over
  // `file`'s vertices, at cache_frames_per_sec (0: the scene's frames_per_sec). Resolved paths
  // set by the loader.
  std::string point_cache, sequence;
  std::filesystem::path point_cache_path, sequence_path;
  double cache_frames_per_sec = 0;

  bool operator==(const MeshColliderParams&) const = default;
};

struct SimulationParams {
  double frames_per_sec = 90;
  int simulation_steps = 30;
  // The initial perturbation (docs/model.md, "Seed"): 0 the classic cloth, N > 0 another draw of it.
  int seed = 0;
  glm::dvec3 gravity{0, -9.8, 0};
  double max_stretch = 0.1;
  double max_speed = 0;  // m/s: no free mass moves further than max_speed * dt in a substep's integration; 0 = no limit
  int constraint_iterations = 1;
  bool self_collision = true;
  Solver solver = Solver::Classic;
  int stretch_passes = -1;       // fabric: Provot passes over every colour after the sweep; -1 auto (stretch_passes_for)
  double sewing_speed = 0.5;     // m/s: how fast a seam's springs shrink from the pair's distance to zero
  int stretch_passes_max = -1;   // up to this many in all, the ones past stretch_passes only while a spring is over; -1: stretch_passes

  bool operator==(const SimulationParams&) const = default;
};

// Deterministic gusts: the wind velocity at x is velocity * (1 + strength * wave(t/period -
// (x . unit velocity)/length)), wave a parabolic stand-in for sin(2 pi phase) (docs/model.md).
struct GustParams {
  double strength = 0.5;  // fraction of the velocity
  double period = 2;      // s
  double length = 4;      // m, the gusts' wavelength along the wind

  bool operator==(const GustParams&) const = default;
};

// Aerodynamic drag and lift on every triangle (docs/model.md, "Wind").
struct WindParams {
  glm::dvec3 velocity{0.0};     // m/s, of the air
  double drag_coefficient = 1.2;  // along the triangle normal (a flat plate across the flow: about 1.2)
  double lift_coefficient = 0.3;  // across the relative velocity
  double air_density = 1.225;     // kg/m^3, sea-level air
  std::optional<GustParams> gust;

  bool operator==(const WindParams&) const = default;
};

struct Scene {
  std::string source;  // file name used in messages ("<built-in>" for the default scene)
  ClothParams cloth;   // the first (or only) cloth: `--set cloth.KEY` edits this one
  // `cloth` written as an array: the cloths after the first, each with its own material. All
  // cloths share the simulation (substeps, solver, self-collision: they collide with each other).
  std::vector<ClothParams> extra_cloths;
  std::vector<SphereParams> spheres;  // applied in file order
  std::vector<PlaneParams> planes;    // applied in file order
  std::vector<MeshColliderParams> meshes;  // applied after the planes, in file order
  SimulationParams simulation;
  std::optional<WindParams> wind;     // absent: no air at all (the classic model)

  std::string name() const;  // file stem, for titles and output names
  double dt() const { return 1.0 / simulation.frames_per_sec / simulation.simulation_steps; }
  // Of the grid cloths (a mesh's count is known once it is loaded: ClothModel::count()).
  int particle_count() const;
  std::vector<const ClothParams*> cloths() const;  // &cloth, then every extra cloth
};

// Bad input: the message already names the file, the key path and what was expected.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Largest grid accepted: keeps every buffer of the GPU and CPU paths well inside memory
// and 32-bit indices (4096 x 4096 particles, about 1.3 GiB of simulation state on the CPU).
inline constexpr long long kMaxParticles = 4096LL * 4096LL;

// `overrides` are "key.path=value" strings from --set, applied before validation.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
Scene parse_scene(const std::string& json_text, const std::string& source,
                  const std::vector<std::string>& overrides = {});
// The classic pinned2 scene, used when no scene is given.
Scene default_scene(const std::vector<std::string>& overrides = {});
// The scene as JSON in the extended format (loads back to the same Scene).
std::string scene_to_json(const Scene& scene);

// A collider as a scene names it: "sphere", "sphere[1]", "plane", "plane[0]", "mesh[2]" (no
// index: the first). kind 1 sphere, 2 plane, 3 mesh; empty when the scene has no such collider.
struct ColliderRef {
  int kind = 0;
  size_t index = 0;
};
std::optional<ColliderRef> find_collider(const Scene& scene, const std::string& key);

}  // namespace clothsim

// THE scene parameter table: every scene parameter is one row here, or for a mesh collider in
// scene_table_mesh.cpp (param_table.hpp says what a row holds and who reads it). Adding a
// parameter: a member in scene.hpp with its default, one row below, and its physics; then
// `cmake --build build --target parameters-doc`.
//
// Row order is the order the loader reads and reports errors in. Ranges are what the loader
// accepts; `expected` is its message for a number outside them (tests/scenes_bad/expected.txt).
#include <algorithm>
#include <cmath>
#include <limits>
#include "scene/scene_table.hpp"
#include "scene/scene_table_detail.hpp"

namespace clothsim {
namespace {

using namespace table_detail;

// `cloth`: one object, or an array of them; the first is Scene::cloth, the rest extra_cloths.
class ClothList final : public ListRef {
 public:
  explicit ClothList(Scene& s) : s_(s) {}
  size_t size() const override { return 1 + s_.extra_cloths.size(); }
  void resize(size_t n) override {
    if (n == 0) s_.cloth = ClothParams{};  // never left so: the loader rejects an empty array
    s_.extra_cloths.resize(n == 0 ? 0 : n - 1);
  }
  void visit(size_t i, ParamVisitor& v) override { visit_rows(i == 0 ? s_.cloth : s_.extra_cloths[i - 1], v); }
  void visit_default(ParamVisitor& v) override { ClothParams d{}; visit_rows(d, v); }
 private:
  Scene& s_;
};

void visit_cloths(Scene& s, const ParamInfo& info, ParamVisitor& v) {
  ClothList l(s);
  v.list(info, l);
}

const char* const kSolvers[] = {"classic", "fabric"};
// Solvers a scene may still name, each refused with what to use instead (docs/solvers.md,
// "Removed solvers"): both became fabric (issue 43).
const RemovedChoice kRemovedSolvers[] = {
    {"xpbd", "the xpbd solver was removed (it softened with resolution and let cloth slide off curved colliders): "
             "use \"fabric\", or \"classic\" for the CS184 model (docs/solvers.md, \"Removed solvers\")"},
    {"multigrid", "the multigrid solver became \"fabric\" (the same multigrid solve with an adaptive start and "
                  "friction in its sweep): use \"fabric\" (docs/solvers.md, \"Removed solvers\")"},
};
const char* const kMassLumpings[] = {"area", "uniform"};

const Param<Scene> kScene[] = {
    // Scene::cloth and Scene::extra_cloths; the panel shows the rows of every cloth.
    {{.key = "cloth", .required = true,
      .meaning = "The cloth: one object, or an array of them, each a grid or a mesh cloth with its own keys",
      .widget = {.style = Widget::Drag}, .one_or_many = true, .single_as_object = true},
     &visit_cloths},
    row<&Scene::spheres>({.key = "sphere", .meaning = "Sphere colliders, applied in order: one object or an array",
                          .one_or_many = true}),
    row<&Scene::planes>({.key = "plane", .meaning = "Plane colliders, applied after the spheres: one object or an array",
                         .one_or_many = true}),
    row<&Scene::meshes>({.key = "mesh", .meaning = "Triangle-mesh colliders through their signed distance fields, "
                                                   "applied after the planes: one object or an array",
                         .one_or_many = true}),
    row<&Scene::simulation>({.key = "simulation", .meaning = "Time stepping and global forces"}),
    // The checkbox: the viewer can add or remove the wind live.
    row<&Scene::wind>({.key = "wind", .meaning = "Air: aerodynamic drag and lift on every triangle of the cloth",
                       .widget = kCheckbox}),
};

const Param<MotionParams> kMotion[] = {
    row<&MotionParams::keyframes>({.key = "keyframes", .required = true, .unit = "s, m",
                                   .meaning = "[t, [x, y, z]] keys: linear between them, held before the first "
                                              "and after the last"}),
};

// num_width_points..orientation need a new cloth: the viewer shows them read-only (Reload).
constexpr Shape kGrid = Shape::Grid, kMesh = Shape::Mesh;
constexpr const char* kSizeFromFile = "a mesh cloth takes its size from the file; remove one of the two";
constexpr const char* kPinsOfGrid = "a grid cloth pins with {}pinned";
constexpr const char* kPlacedByOrientation = "a grid cloth is placed by {}orientation";
const Param<ClothParams> kCloth[] = {
    row<&ClothParams::width>({.key = "width", .required = true, .lo = 1e-9, .expected = "a size > 0 (metres)",
                              .unit = "m", .meaning = "extent along x", .widget = kReadOnly, .shape = kGrid,
                              .instead = kSizeFromFile}),
    row<&ClothParams::height>({.key = "height", .required = true, .lo = 1e-9, .expected = "a size > 0 (metres)",
                               .unit = "m", .meaning = "extent along z (horizontal) or y (vertical)",
                               .widget = kReadOnly, .shape = kGrid, .instead = kSizeFromFile}),
    row<&ClothParams::num_width_points>({.key = "num_width_points", .required = true, .lo = 2, .hi = 1 << 20,
                                         .meaning = "point masses along the width (at most 4096² in all)",
                                         .widget = kReadOnly, .shape = kGrid, .instead = kSizeFromFile}),
    row<&ClothParams::num_height_points>({.key = "num_height_points", .required = true, .lo = 2, .hi = 1 << 20,
                                          .meaning = "point masses along the height", .widget = kReadOnly,
                                          .shape = kGrid, .instead = kSizeFromFile}),
    row<&ClothParams::thickness>({.key = "thickness", .required = true, .lo = 1e-9,
                                  .expected = "a thickness > 0 (metres)", .unit = "m",
                                  .meaning = "self-collision keeps masses 2 · thickness apart",
                                  .widget = drag(0.0005f, 1e-4, 1.0, "%.4f")}),
    row<&ClothParams::orientation>({.key = "orientation", .required = true, .lo = 0, .hi = 1,
                                    .meaning = "0: flat at y = 1 spanning x and z; 1: standing in the x–y plane",
                                    .widget = kReadOnly, .shape = kGrid, .instead = kSizeFromFile}),
    // Special case: a list of [x, y] grid indices, checked against the grid (and the grid
    // against memory) by the loader's grid_indices.
    row<&ClothParams::pinned>({.key = "pinned", .meaning = "[x, y] grid indices of masses that never move",
                               .shape = kGrid,
                               .instead = "a mesh cloth pins with {}pinned_vertices or {}pinned_box; remove one "
                                          "of the two"}),
    row<&ClothParams::enable_structural>({.key = "enable_structural", .meaning = "x±1 and y±1 springs exert force",
                                          .widget = kCheckbox}),
    row<&ClothParams::enable_shearing>({.key = "enable_shearing", .meaning = "diagonal springs exert force",
                                        .widget = kCheckbox}),
    row<&ClothParams::enable_bending>({.key = "enable_bending", .meaning = "x±2 and y±2 springs exert force",
                                       .widget = kCheckbox}),
    row<&ClothParams::damping>({.key = "damping", .lo = 0, .hi = 100, .expected = "a percentage in [0, 100]",
                                .unit = "%", .meaning = "the Verlet velocity term is scaled by (1 - damping/100)",
                                .widget = drag(0.01f, 0.0, 100.0, "%.3f")}),
    // Shown in g/cm^2 like the classic GUI (1 g/cm^2 = 10 kg/m^2).
    row<&ClothParams::density>({.key = "density", .lo = 1e-12, .expected = "a density > 0 (kg/m^2)",
                                .unit = "kg/m^2", .meaning = "mass per area; each mass is width · height · density / points",
                                .widget = {.style = Widget::Drag, .speed = 0.1f, .lo = 0.01, .hi = 1000,
                                           .format = "%.2f", .scale = 0.1, .unit = "g/cm^2"}}),
    row<&ClothParams::ks>({.key = "ks", .lo = 0, .expected = "a spring constant >= 0 (N/m)", .unit = "N/m",
                           .meaning = "spring constant; bending springs use 0.2 · ks",
                           .widget = drag(10.f, 0.0, 1e7, "%.0f")}),
    row<&ClothParams::attachments>({.key = "attachments",
                                    .meaning = "cloth vertices tied to a collider, which they follow (docs/model.md, "
                                               "\"Attachments\"): a list of objects"}),
    row<&ClothParams::seams>({.key = "seams",
                              .meaning = "cloth vertices sewn to others of this cloth or of another (docs/model.md, "
                                         "\"Sewing\"): a list of objects"}),
    row<&ClothParams::pinned_motion>({.key = "pinned_motion",
                                      .meaning = "moves every pinned mass: keys are offsets [dx, dy, dz] from "
                                                 "its start"}),
    // A cloth from a mesh file instead of the grid (docs/model.md, "Mesh cloth"): with `mesh`
    // the grid rows above must be absent, without it these.
    row<&ClothParams::mesh>({.key = "mesh", .expected = "a path to a mesh file",
                             .meaning = "a mesh file (OBJ, PLY, glTF, STL, ...), relative to the scene file: "
                                        "its vertices are the masses, its edges the springs",
                             .widget = kReadOnly, .shape = kMesh}),
    row<&ClothParams::pinned_vertices>({.key = "pinned_vertices", .lo = 0,
                                        .expected = "a vertex index >= 0",
                                        .meaning = "0-based indices, in the file's vertex order, of masses that "
                                                   "never move",
                                        .widget = kReadOnly, .shape = kMesh, .instead = kPinsOfGrid}),
    row<&ClothParams::pinned_box>({.key = "pinned_box",
                                   .meaning = "every vertex inside the box (after scale, rotation, offset; "
                                              "inclusive) is pinned too",
                                   .shape = kMesh, .instead = kPinsOfGrid}),
    row<&ClothParams::scale>({.key = "scale", .lo = 1e-9, .expected = "a scale > 0",
                              .meaning = "the file's coordinates are multiplied by this (metres per unit)",
                              .widget = kReadOnly, .shape = kMesh,
                              .instead = "a grid cloth's size is {}width and {}height"}),
    row<&ClothParams::offset>({.key = "offset", .unit = "m", .meaning = "added to every vertex, last",
                               .widget = kReadOnly, .shape = kMesh, .instead = kPlacedByOrientation}),
    row<&ClothParams::rotation_axis>({.key = "rotation_axis",
                                      .meaning = "non-zero; made unit length on loading",
                                      .widget = kReadOnly, .shape = kMesh, .instead = kPlacedByOrientation,
                                      .after_read = normalise_axis}),
    row<&ClothParams::rotation_degrees>({.key = "rotation_degrees", .unit = "°",
                                         .meaning = "rotation about rotation_axis (right-handed), after the scale",
                                         .widget = kReadOnly, .shape = kMesh, .instead = kPlacedByOrientation}),
    row<&ClothParams::mass_lumping>({.key = "mass_lumping",
                                     .meaning = "area: each vertex gets a share of the area of its faces; "
                                                "uniform: every vertex the same mass",
                                     .widget = kReadOnly, .choices = kMassLumpings, .shape = kMesh,
                                     .instead = "a grid cloth's masses are all equal"}),
    row<&ClothParams::material>({.key = "material",
                                 .meaning = "a fabric in physical units (fabric solver): a preset's name (\"silk\", "
                                            "\"cotton\", \"wool\", \"denim\", \"leather\") or an object; replaces "
                                            "density, ks and the springs (docs/materials.md)",
                                 .string_as = "preset"}),
};

// cloth.material (docs/materials.md): 0 takes the preset's value (resolve_material).
const Param<MaterialParams> kMaterial[] = {
    row<&MaterialParams::preset>({.key = "preset", .expected = "a preset: \"silk\", \"cotton\", \"wool\", \"denim\" or \"leather\"",
                                  .meaning = "its values fill every key below that is absent", .widget = kReadOnly}),
    row<&MaterialParams::density>({.key = "density", .lo = 0, .expected = "a density > 0 (kg/m^2)", .unit = "kg/m^2",
                                   .meaning = "mass per area (absent: the preset's)", .widget = drag(0.001f, 1e-4, 100.0, "%.4f")}),
    row<&MaterialParams::stretch>({.key = "stretch", .lo = 0, .expected = "a stiffness > 0 (N/m)", .unit = "N/m",
                                   .meaning = "uniaxial tensile stiffness (force per width over strain), warp and "
                                              "weft (absent: the preset's)", .widget = drag(10.f, 1.0, 1e6, "%.0f")}),
    row<&MaterialParams::shear>({.key = "shear", .lo = 0, .expected = "a shear stiffness > 0 (N/m)", .unit = "N/m",
                                 .meaning = "in-plane shear modulus (force per width over shear angle; absent: the preset's)",
                                 .widget = drag(0.5f, 0.01, 1e5, "%.2f")}),
    row<&MaterialParams::bending>({.key = "bending", .lo = 0, .expected = "a bending rigidity > 0 (N·m)", .unit = "N·m", .meaning =
        "bending rigidity (moment per width over curvature), warp and weft (absent: the preset's; a new value rebuilds the cloth)", .widget = kReadOnly}),
    row<&MaterialParams::compression>({.key = "compression", .lo = 0, .hi = 1, .expected = "a ratio in (0, 1]", .meaning =
        "a shortened direction's stiffness over its stretch, as fabric buckles (absent: the preset's)", .widget = drag(0.01f, 0.01, 1.0, "%.2f")}),
};

const Param<BoxParams> kBox[] = {
    row<&BoxParams::min>({.key = "min", .required = true, .unit = "m", .meaning = "lowest corner (each of x, y, z <= max's)"}),
    row<&BoxParams::max>({.key = "max", .required = true, .unit = "m", .meaning = "highest corner"}),
};

const Param<AttachmentParams> kAttachment[] = {
    row<&AttachmentParams::collider>({.key = "collider", .required = true,
                                      .expected = "a collider of the scene: \"sphere\", \"sphere[1]\", \"plane[0]\", "
                                                  "\"mesh[0]\", ...",
                                      .meaning = "the collider the vertices follow: sphere, plane or mesh, with [k] "
                                                 "for the k-th of several"}),
    row<&AttachmentParams::vertices>({.key = "vertices",
                                      .meaning = "0-based indices of the attached vertices (a grid's row-major: "
                                                 "y · num_width_points + x)"}),
    row<&AttachmentParams::box>({.key = "box", .meaning = "every vertex whose start position is inside (inclusive)"}),
    row<&AttachmentParams::stiffness>({.key = "stiffness", .lo = 1e-9, .hi = 1e9,
                                       .expected = "a stiffness in [1e-9, 1e9] (N/m)", .unit = "N/m",
                                       .meaning = "of each vertex's zero-length spring to its anchor",
                                       .widget = drag(10.f, 1e-9, 1e9, "%.1f")}),
};

// One side of a seam is `vertices`, `edge` or `box` (scene.cpp checks there is one); the other
// is the to_ keys, on `to_cloth`.
const Param<SeamParams> kSeam[] = {
    row<&SeamParams::vertices>({.key = "vertices", .lo = 0, .expected = "a vertex index >= 0", .meaning = "0-based indices of this side's vertices, in order"}),
    row<&SeamParams::edge>({.key = "edge", .expected = "\"x_min\", \"x_max\", \"y_min\" or \"y_max\"",
                            .meaning = "a grid's side: the column x = 0 or the last, the row y = 0 or the last, "
                                       "in ascending grid index"}),
    row<&SeamParams::box>({.key = "box", .meaning = "every vertex whose start position is inside, ordered along "
                                                   "the box's longest side"}),
    row<&SeamParams::to_cloth>({.key = "to_cloth", .lo = -1, .hi = 1 << 20,
                                .expected = "the 0-based index of a cloth of the array",
                                .meaning = "the cloth of the other side; absent: this one"}),
    row<&SeamParams::to_vertices>({.key = "to_vertices", .lo = 0, .expected = "a vertex index >= 0", .meaning = "the other side's vertices: its k-th is sewn to "
                                                                   "this side's k-th"}),
    row<&SeamParams::to_edge>({.key = "to_edge", .expected = "\"x_min\", \"x_max\", \"y_min\" or \"y_max\"",
                               .meaning = "the other side as a grid's side"}),
    row<&SeamParams::to_box>({.key = "to_box", .meaning = "the other side as the vertices inside a box"}),
};

const Param<SphereParams> kSphere[] = {
    row<&SphereParams::origin>({.key = "origin", .required = true, .unit = "m", .meaning = "centre"}),
    row<&SphereParams::radius>({.key = "radius", .required = true, .lo = 1e-12, .expected = "a radius > 0 (metres)",
                                .unit = "m", .meaning = "radius"}),
    row<&SphereParams::friction>(kFriction),
    row<&SphereParams::motion>({.key = "motion", .meaning = "keyframed origin, in place of `origin`; friction "
                                                            "acts relative to it"}),
};

const Param<PlaneParams> kPlane[] = {
    row<&PlaneParams::point>({.key = "point", .required = true, .unit = "m", .meaning = "a point on the plane"}),
    row<&PlaneParams::normal>({.key = "normal", .required = true,
                               .meaning = "non-zero, either sign; made unit length on loading",
                               .after_read = normalise_normal}),
    row<&PlaneParams::friction>(kFriction),
    row<&PlaneParams::motion>({.key = "motion", .meaning = "keyframed point, in place of `point` (the plane "
                                                           "translates); friction acts relative to it"}),
};

const Param<SimulationParams> kSimulation[] = {
    row<&SimulationParams::frames_per_sec>({.key = "frames_per_sec", .lo = 1e-6, .hi = 1e6,
                                            .expected = "frames per second in (0, 1e6]", .unit = "1/s",
                                            .meaning = "frames per simulated second",
                                            .widget = drag(1.f, 1.0, 1000.0, "%.0f")}),
    row<&SimulationParams::simulation_steps>({.key = "simulation_steps", .lo = 1, .hi = 100000,
                                              .meaning = "substeps per frame; dt = 1 / frames_per_sec / simulation_steps",
                                              .widget = drag(1.f, 1, 1000, "%d")}),
    row<&SimulationParams::seed>({.key = "seed", .lo = 0, .hi = 2147483647, .meaning = "initial jitter: 0 classic, "
                                  "N > 0 redrawn for every cloth (--seeds)", .widget = kReadOnly}),
    row<&SimulationParams::gravity>({.key = "gravity", .unit = "m/s^2", .meaning = "acceleration of every mass",
                                     .widget = drag(0.05f, 0, 0, "%.3f")}),
    row<&SimulationParams::max_stretch>({.key = "max_stretch", .lo = 0, .expected = "a stretch ratio >= 0",
                                         .meaning = "no spring ends a substep longer than (1 + max_stretch) · rest",
                                         .widget = drag(0.005f, 0.0, 10.0, "%.3f")}),
    row<&SimulationParams::max_speed>({.key = "max_speed", .lo = 0, .expected = "a speed >= 0", .unit = "m/s",
                                       .meaning = "speed clamp: a free mass's move in a substep's integration (Verlet's "
                                                  "or fabric's prediction) is at most max_speed · dt, against the explosions "
                                                  "of fast colliders and large time steps; 0: no limit",
                                       .widget = drag(0.05f, 0.0, 1000.0, "%.2f")}),
    row<&SimulationParams::constraint_iterations>({.key = "constraint_iterations", .lo = 0, .hi = 10000,
                                                   .meaning = "classic: sweeps of the length constraint per substep (fabric solves its springs in its own sweep)",
                                                   .widget = drag(0.1f, 0, 100, "%d")}),
    row<&SimulationParams::self_collision>({.key = "self_collision", .meaning = "hashed-grid self-collision on/off",
                                            .widget = kCheckbox}),
    row<&SimulationParams::solver>({.key = "solver",
                                    .meaning = "classic: mass-spring + Verlet + Provot (CS184); fabric: implicit "
                                               "Euler per substep, a multigrid V-cycle and a vertex sweep with contacts "
                                               "and friction, as stiff at any resolution, started from the inertial "
                                               "prediction so a falling or buckling cloth keeps its pace "
                                               "(docs/solvers.md); \"xpbd\" and \"multigrid\" were removed",
                                    .widget = {.style = Widget::Drag},  // a combo box
                                    .choices = kSolvers, .removed_choices = kRemovedSolvers}),
    row<&SimulationParams::stretch_passes>(
        {.key = "stretch_passes", .lo = -1, .hi = 100, .expected = "-1 (auto) or a pass count in [0, 100]",
         .meaning = "fabric: passes of the max_stretch limit over every colour after the sweep, so that "
                    "the limit holds at the end of the substep (in the sweep a later colour can pull a spring out "
                    "again); -1: 2 where a cloth's own weight would stretch its "
                    "springs past half the limit (density · |gravity| · size / ks > max_stretch / 2), else 1 with "
                    "seams (their weld), else none",
         .widget = drag(0.1f, -1, 20, "%d")}),
    row<&SimulationParams::sewing_speed>({.key = "sewing_speed", .lo = 1e-6, .hi = 1e3,
                                          .expected = "a speed in [1e-6, 1e3] (m/s)", .unit = "m/s",
                                          .meaning = "a seam's springs shrink from the pair's start distance to zero "
                                                     "at this speed, then hold the pair together (docs/model.md, "
                                                     "\"Sewing\")",
                                          .widget = drag(0.01f, 1e-6, 1e3, "%.2f")}),
    row<&SimulationParams::stretch_passes_max>(
        {.key = "stretch_passes_max", .lo = -1, .hi = 100, .expected = "-1 (no settling passes) or a pass count in [0, 100]",
         .meaning = "fabric: settling passes of the limit after the stretch_passes ones, up to this many "
                    "passes in all, each only while the pass before it found a spring longer than (1 + 2^-16) times "
                    "its limit: the limit holds where one event needs many passes, and a quiet substep pays "
                    "for none (docs/model.md); -1: 16 in all where stretch_passes is auto and gives 2 (a cloth "
                    "resting on its limit), else none; a count not above stretch_passes: none",
         .widget = drag(0.1f, -1, 40, "%d")}),
};

const Param<WindParams> kWind[] = {
    row<&WindParams::velocity>({.key = "velocity", .unit = "m/s",
                                .meaning = "of the air; [0, 0, 0] still leaves air resistance",
                                .widget = drag(0.05f, 0, 0, "%.2f")}),
    row<&WindParams::drag_coefficient>({.key = "drag_coefficient", .lo = 0, .hi = 100, .expected = "a coefficient in [0, 100]",
                                        .meaning = "C_d: force along the triangle normal, ½ ρ C_d A |v| (v·n)",
                                        .widget = drag(0.01f, 0.0, 100.0, "%.2f")}),
    row<&WindParams::lift_coefficient>({.key = "lift_coefficient", .lo = 0, .hi = 100, .expected = "a coefficient in [0, 100]",
                                        .meaning = "C_l: force across the relative velocity, ½ ρ C_l A |v| (v·n)",
                                        .widget = drag(0.01f, 0.0, 100.0, "%.2f")}),
    row<&WindParams::air_density>({.key = "air_density", .lo = 0, .hi = 1e4, .expected = "a density in [0, 1e4] (kg/m^3)",
                                   .unit = "kg/m^3", .meaning = "ρ (sea-level air: 1.225)",
                                   .widget = drag(0.01f, 0.0, 100.0, "%.3f")}),
    row<&WindParams::gust>({.key = "gust", .meaning = "deterministic gusts travelling with the wind",
                            .widget = kCheckbox}),
};

const Param<GustParams> kGust[] = {
    row<&GustParams::strength>({.key = "strength", .lo = 0, .hi = 10, .expected = "a fraction in [0, 10]",
                                .meaning = "the wind speed swings by ± this fraction of `velocity`",
                                .widget = drag(0.01f, 0.0, 10.0, "%.2f")}),
    row<&GustParams::period>({.key = "period", .lo = 1e-3, .hi = 1e6, .expected = "a period in [1e-3, 1e6] (seconds)",
                              .unit = "s", .meaning = "time between two gusts at one place",
                              .widget = drag(0.01f, 0.001, 1000.0, "%.2f")}),
    row<&GustParams::length>({.key = "length", .lo = 1e-3, .hi = 1e6, .expected = "a length in [1e-3, 1e6] (metres)",
                              .unit = "m", .meaning = "distance between two gusts along the wind",
                              .widget = drag(0.01f, 0.001, 1000.0, "%.2f")}),
};

}  // namespace

template <> std::span<const Param<Scene>> param_rows<Scene>() { return kScene; }
template <> std::span<const Param<ClothParams>> param_rows<ClothParams>() { return kCloth; }
template <> std::span<const Param<SphereParams>> param_rows<SphereParams>() { return kSphere; }
template <> std::span<const Param<PlaneParams>> param_rows<PlaneParams>() { return kPlane; }
template <> std::span<const Param<SimulationParams>> param_rows<SimulationParams>() { return kSimulation; }
template <> std::span<const Param<MotionParams>> param_rows<MotionParams>() { return kMotion; }
template <> std::span<const Param<WindParams>> param_rows<WindParams>() { return kWind; }
template <> std::span<const Param<GustParams>> param_rows<GustParams>() { return kGust; }
template <> std::span<const Param<BoxParams>> param_rows<BoxParams>() { return kBox; }
template <> std::span<const Param<AttachmentParams>> param_rows<AttachmentParams>() { return kAttachment; }
template <> std::span<const Param<SeamParams>> param_rows<SeamParams>() { return kSeam; }
template <> std::span<const Param<MaterialParams>> param_rows<MaterialParams>() { return kMaterial; }

}  // namespace clothsim

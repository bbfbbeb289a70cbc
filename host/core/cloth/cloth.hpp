// The cloth model (docs/model.md, "The cloth model"): everything about the cloth that never
// changes during a run, built once from the scene and read by every pass of both backends.
// One model for every shape: particles, triangles and explicit spring lists. The CS184 grid
// (cloth_grid.cpp) and a mesh file (cloth_mesh.cpp) are two builders of it; a scene with
// several cloths is one model whose parts follow each other in the arrays.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace clothsim {

// Seam: a spring of cloth.seams (seams.cpp), across a seam between two vertices that start
// apart; its rest length shrinks to zero as the seam closes (docs/model.md, "Sewing").
enum class SpringType { Structural = 0, Shearing = 1, Bending = 2, Seam = 3 };
inline constexpr int kSpringTypes = 4;

// One spring (a distance constraint under xpbd): from particle i to j, with its rest length,
// its type (which stiffness, which enable_* flag) and the cloth whose material it takes.
struct Spring {
  uint32_t i = 0, j = 0;
  double rest = 0;
  SpringType type = SpringType::Structural;
  uint32_t material = 0;  // index of the cloth in Scene::cloths()
};

// One cloth of the scene: its ranges in the model's arrays.
struct ClothPart {
  uint32_t first = 0, count = 0;                    // particles
  uint32_t first_triangle = 0, triangle_count = 0;
  int nw = 0, nh = 0;                                 // a grid's size; 0 for a mesh
  std::string mesh;                                   // the mesh file, empty for a grid
};

// A cloth with a material (docs/materials.md) takes its forces from its triangles and hinges,
// not its springs (which stay for the colouring and the coarse levels; its gather keeps only
// its seams). Each particle lists its own entries, so the fabric sweep gathers them like springs:
// A triangle seen from one corner i: its other corners a, b (the triangle's order from i) and
// its rest shape in the material's frame (metres along warp u and weft v): dminv is
// [ua - ui, ub - ui]^-1 row-major, area its rest area.
struct MembraneEntry {
  uint32_t a = 0, b = 0;
  double area = 0;
  std::array<double, 4> dminv{};
};
// A bending hinge (an edge between two triangles) seen from one of its four particles: the
// others, and the weights of v = k0 x_self + k1 x_o0 + k2 x_o1 + k3 x_o2, the quadratic bending
// model's curvature vector (Bergou et al. 2006) scaled by sqrt(B c) so its energy is
// 1/2 (|v| - rest)^2; rest is |v| at the rest shape (0 for a flat cloth).
struct HingeEntry {
  std::array<uint32_t, 3> other{};
  double rest = 0;
  std::array<double, 4> k{};
};
// The hinges and stencils with a flat rest (rest 0) have the energy 1/2 x^T Q x, Q = the sum of
// their k k^T: constant, so they are summed once, into Q's rows (Bergou et al. 2006). Particle
// i's row: Q_ii first (other = i), then Q_ij by ascending j, padded to an even count with
// (i, 0); its force is -sum Q_ij (x_j - x_i) (a row sums to 0), its block Q_ii I.
struct BendEntry {
  uint32_t other = 0;
  double weight = 0;
};

struct ClothModel {
  // Particles.
  std::vector<glm::dvec3> initial;   // start positions
  std::vector<double> area;          // the cloth area each mass stands for (m^2): mass = density x area
  std::vector<double> mass;          // kg, at the scene's densities when built (particle_masses)
  std::vector<uint8_t> pinned;       // 1 = never moves
  std::vector<glm::dvec2> uv;
  std::vector<uint32_t> material;    // the particle's cloth (index into Scene::cloths())
  // For shading: the particles before and after each one along +u, whose difference is the
  // tangent (a grid's x - 1 and x + 1, one-sided at the edges).
  std::vector<std::array<uint32_t, 2>> tangent_ends;
  std::vector<std::array<uint32_t, 3>> triangles;
  // Springs sorted by colour: colour c is springs [colour_start[c], colour_start[c + 1]), all of
  // one type, no two sharing a particle, so a colour is one dispatch without atomics. Colours run
  // structural, then shearing, then bending, then seams: one Gauss-Seidel sweep visits them in
  // this order.
  std::vector<Spring> springs;
  std::vector<uint32_t> colour_start;
  // The classic force gather: particle i sums springs gather[gather_start[i] .. gather_start[i + 1])
  // (indices into springs) in this fixed order, on both backends.
  std::vector<uint32_t> gather_start, gather;
  // The triangles around each particle, ascending (normals and the wind gather over them).
  std::vector<uint32_t> corner_start, corner_triangles;
  std::vector<ClothPart> parts;
  // With seams: per particle the least particle it is sewn to, through any chain of seams (itself
  // if none). Self-collision never pushes two particles of one weld apart. Empty without seams.
  std::vector<uint32_t> weld;
  // Per particle its membrane entries [membrane_start[i], membrane_start[i + 1]), its row of
  // flat bending entries and its curved hinge entries likewise (fabric_terms.cpp); all empty
  // when no cloth has a material.
  std::vector<uint32_t> membrane_start, bend_start, hinge_start;
  std::vector<MembraneEntry> membrane;
  std::vector<BendEntry> bend;
  std::vector<HingeEntry> hinges;
  // The grid's size when the whole model is one CS184 grid (row-major i = y * nw + x), else 0.
  int nw = 0, nh = 0;

  int count() const { return int(initial.size()); }
  int index(int x, int y) const { return y * nw + x; }
  int colours() const { return int(colour_start.size()) - 1; }
  SpringType colour_type(int c) const { return springs[colour_start[c]].type; }
  bool has_seams() const { return !weld.empty(); }
  bool has_material() const { return !membrane_start.empty(); }
  bool is_grid() const { return nw > 0; }
  // Springs of one type (independent of the enable_* flags).
  int springs_of(SpringType type) const;
  int structural_springs() const { return springs_of(SpringType::Structural); }
  int shearing_springs() const { return springs_of(SpringType::Shearing); }
  int bending_springs() const { return springs_of(SpringType::Bending); }
  int seam_springs() const { return springs_of(SpringType::Seam); }
};

// "50x50 cloth", "mesh cloth of 10000 particles, 29500 springs", "2 cloths, 3000 particles": for messages.
std::string describe_cloth(const ClothModel& model);

// Every cloth of the scene, in order, as one model. Throws SceneError for a bad mesh.
// Throws HostOutOfMemory when the model does not fit in memory.
ClothModel build_cloth(const Scene& scene);
// With self-collision on, throws SceneError when it would compare a particle with more than
// kMaxSelfCollisionNeighbours others (a thickness many times the spacing). Called by
// make_constants, so every run (either backend, the viewer) is checked, not a mere model.
inline constexpr double kMaxSelfCollisionNeighbours = 1000;
void check_self_collision_cost(const Scene& scene, const ClothModel& model);

// The pieces the builders share (cloth.cpp). A builder appends one part's particles,
// triangles and springs (each with its colour within its type), then finish_model sorts the
// springs by colour and derives the gather lists and the corner lists.
struct PartSprings {
  std::vector<Spring> springs;
  std::vector<uint32_t> colour;  // per spring, within its type (0, 1, ...)
  // Optional: the force gather order, for each particle of the part its springs (indices into
  // `springs`), each particle's list ended by kEndOfList. Empty: every spring at the particle,
  // in sorted order.
  std::vector<uint32_t> gather;
};
inline constexpr uint32_t kEndOfList = UINT32_MAX;
// `parts` has one entry per model.parts, then optionally the seams' springs (sew_seams), whose
// ends may be in any part: every particle gathers its seams after its own springs.
void finish_model(ClothModel& model, const std::vector<PartSprings>& parts);
// cloth.seams of every cloth as springs of type Seam, each at the pair's start distance, with
// their colours (no two at one particle); sets model.weld. Nothing without seams. Throws
// SceneError for a side with an index out of range, sides of unequal lengths, or a vertex sewn
// to itself.
PartSprings sew_seams(const Scene& scene, ClothModel& model);
// The CS184 grid of `params` appended to `model` as cloth `material` (cloth_grid.cpp), its
// jitter drawn with `seed` (simulation.seed).
PartSprings append_grid(ClothModel& model, const ClothParams& params, uint32_t material, uint32_t seed = 0);
// A mesh cloth appended likewise (cloth_mesh.cpp).
PartSprings append_mesh(ClothModel& model, const Scene& scene, const ClothParams& params, uint32_t material);

// The membrane and hinge entries of every cloth with a material (fabric_terms.cpp); nothing
// when none has one.
void add_fabric_terms(const Scene& scene, ClothModel& model);

// Mass of every particle of a grid: width * height * density / particle count (kg).
double particle_mass(const ClothParams& params);
// The mass of each particle for the scene's densities (a live density edit changes them).
std::vector<double> particle_masses(const Scene& scene, const ClothModel& model);

// The z offset of a vertical cloth's particle i, in [-amplitude, amplitude]: a hash of the
// index and the seed, so the same cloth comes out on every machine and both backends (no std::
// distribution); seed 0 is the classic draw.
double vertical_offset(uint32_t i, double amplitude, uint32_t seed = 0);
// The amplitude for a grid spacing: 1e-3 m (the classic), at most 5 % of the spacing.
double jitter_amplitude(double spacing);

}  // namespace clothsim

// Signed distance fields of triangle meshes, for the mesh colliders (scene key `mesh`,
// docs/model.md, "Mesh colliders"): built once on the CPU, sampled by both backends with the
// same written-out trilinear interpolation (sample_mesh_field in reference_mesh_collisions.cpp,
// compute/collide_meshes.glsl).
//
// The field is node-centred on a regular grid: value (x, y, z) is the distance at
// min + voxel (x, y, z). Within `band` of the surface it is the exact distance to the nearest
// triangle (closest point on each triangle near the node), signed by the angle-weighted
// pseudo-normal of the nearest feature (Baerentzen and Aanaes 2005: exact for a closed mesh);
// beyond the band it is +-band, the sign found by a flood fill from the grid's border (the
// padding keeps the border outside the band). A mesh with boundary edges (an open mesh, as
// most real models are) is signed by its generalised winding number instead (winding.hpp):
// inside where its magnitude is above 1/2, so a hole is closed by that level set and a mass
// cannot slip in through it; a thin open sheet, whose winding number stays under 1/2, keeps an
// unsigned field there and collides as the shell `thickness` around its surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace clothsim {

struct SurfaceMesh {
  std::vector<glm::dvec3> positions;
  std::vector<glm::uvec3> triangles;  // indices into positions, counter-clockwise seen from outside
};

struct SdfGrid {
  glm::dvec3 min{0.0};   // position of node (0, 0, 0)
  double voxel = 0;      // node spacing (m)
  glm::ivec3 dims{0};    // nodes along x, y, z (each >= 2)
  double band = 0;       // |value| is exact below this; beyond it the value is +-band (m)
  bool closed = true;    // false: the mesh has boundary edges; signed by the winding number
  size_t boundary_edges = 0;
  std::vector<float> values;  // x fastest, then y, then z

  size_t nodes() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
  size_t bytes() const { return nodes() * sizeof(float); }
  size_t index(int x, int y, int z) const { return size_t(x) + size_t(dims.x) * (size_t(y) + size_t(dims.y) * size_t(z)); }
  float at(int x, int y, int z) const { return values[index(x, y, z)]; }
};

// The band in voxels: wide enough that no six-connected path of nodes crosses the surface
// without a node in the band (so the flood fill cannot leak), and that a mass moving less than
// the band per substep is always seen on the side it came from.
inline constexpr double kSdfBandVoxels = 3.0;
// Largest field one mesh may take (memory on both backends; the GPU holds it as one buffer).
inline constexpr size_t kMaxSdfBytes = size_t(256) << 20;
// An open mesh's winding numbers (FastWindingNumber's beta): 1.5 decides the sign of Wuson's
// nodes as the exact sum does, at half the cost of 2.
inline constexpr double kSdfWindingAccuracy = 1.5;
// The default node spacing: the mesh's longest extent over this (about 2 MiB for a cube).
inline constexpr double kDefaultSdfDivisions = 128.0;

// Nodes the field of `mesh` at spacing `voxel` takes (padding included), for the memory check;
// a double, since a spacing far too small gives more than a size_t holds.
double sdf_nodes(const SurfaceMesh& mesh, double voxel);
// Builds the field; `voxel` > 0. Throws std::invalid_argument for an empty mesh.
SdfGrid build_sdf(const SurfaceMesh& mesh, double voxel);

// Exact references, every triangle visited (tests; a few thousand points of a small mesh):
// the distance to the closest triangle, and the generalised winding number (1 inside a closed
// mesh, 0 outside; Jacobson et al. 2013), the sign brute_force_signed_distance takes.
double brute_force_distance(const SurfaceMesh& mesh, const glm::dvec3& p);
double winding_number(const SurfaceMesh& mesh, const glm::dvec3& p);
double brute_force_signed_distance(const SurfaceMesh& mesh, const glm::dvec3& p);

// The closest point of triangle (a, b, c) to p, and which feature holds it: 0 the face, 1-3
// the vertex a, b, c, 4-6 the edge ab, bc, ca (Ericson, Real-Time Collision Detection 5.1.5).
glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c, int& feature);

// 64-bit FNV-1a of the mesh's positions and triangles: the cache key with the spacing.
uint64_t mesh_hash(const SurfaceMesh& mesh);

// The cache file format (docs/model.md, "Mesh colliders"): "clothsim sdf\n" magic, version,
// mesh hash, spacing bits, the grid, then a 64-bit FNV-1a checksum of all before it.
// read_sdf_cache returns false for a file that is absent (`problem` left empty) or that fails a
// check: another version, mesh or spacing, truncated, a checksum that does not match
// (`problem` says which); the field is then rebuilt.
bool read_sdf_cache(const std::filesystem::path& file, uint64_t hash, double voxel, SdfGrid& out,
                    std::string* problem = nullptr);
void write_sdf_cache(const std::filesystem::path& file, uint64_t hash, const SdfGrid& grid);

}  // namespace clothsim

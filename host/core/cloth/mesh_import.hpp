// A cloth from a polygon mesh file (OBJ, PLY, glTF, STL, ... anything Assimp reads): the
// particles, their uv and the faces, for build_mesh_springs (mesh_springs.hpp).
//
// Particle order, which is what `cloth.pinned_vertices` (0-based) and every export index by:
//
// * OBJ (.obj, any case): the file's `v` lines, in file order. An OBJ with N `v` lines gives
//   N particles, particle i at `v` line i, and its position is the line's numbers read as
//   doubles (std::from_chars), exactly as written (Assimp itself keeps floats only). A `v`
//   line that no face uses is kept as a free particle with no springs (it falls), so indices
//   stay file indices. `v x y z w` is (x/w, y/w, z/w) and `v x y z r g b` is (x, y, z), as in
//   Assimp. Why the extra reading: Assimp 5.2 builds one vertex per face corner, in face
//   order, and drops unused `v` lines, so its order is "first use by the faces", not the
//   file's. Each Assimp vertex is mapped back to its `v` line by its position (exact float
//   bits first, then the nearest within 2 float ulps per coordinate, since Assimp's own
//   number parser is off by one ulp for about 3% of 17-digit coordinates). Two `v` lines
//   at the same position (as floats) cannot be told apart: the faces use the first, the
//   later one is a free particle. Should a vertex match no `v` line (a file Assimp reads
//   differently, e.g. UTF-16), a warning says so and the rule below is used instead.
// * Every other format: Assimp's vertex arrays in order, walking the node tree depth first
//   (a node's meshes in order, then its children), each vertex transformed by its node's
//   accumulated transform; a vertex at exactly the position of an earlier one is that
//   particle (welded). For PLY and glTF that is the file's vertex order, unused vertices
//   kept, minus exact duplicates (a glTF uv seam's second copy is welded into the first).
//   STL has no shared vertices: the order is that of first appearance among the facets.
//   Positions are Assimp's (single precision) after the transform.
//
// Welding is by exact position only, regardless of uv or normals (a uv seam is one
// particle, which keeps the first uv met). Several meshes or objects make one PolyMesh.
//
// uv: from Assimp's first texture-coordinate channel when every mesh with faces has one
// (the first uv met per particle; (0, 0) for particles no face uses), otherwise empty.
//
// Faces: triangles and quads as in the file, in its winding, meshes in the order above.
// A polygon with more than 4 corners becomes a fan of triangles from its first corner (right
// for convex polygons, which is what cloth meshes hold). Points and lines are ignored (one
// warning line). A face with a repeated particle or with zero area (relative to its longest
// edge squared, 1e-12) is dropped, with one warning line on stderr giving the count.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

struct aiMesh;
struct aiNode;
struct aiScene;

namespace clothsim {

// The largest cloth accepted from a file (2^24 particles).
inline constexpr size_t kMaxMeshVertices = size_t(1) << 24;

struct PolyMesh {
  std::vector<glm::dvec3> positions;         // one per particle, in the order described above
  std::vector<glm::dvec2> uv;                // same size as positions, or empty when the file has no uv
  std::vector<std::vector<uint32_t>> faces;  // each 3 (triangle) or 4 (quad) particle indices, in the file's winding
};

// One use of an aiMesh by a node of the file: the node's transform accumulated from the root,
// and the particle each of its vertices became (welded as above).
struct MeshUse {
  const aiMesh* mesh;
  const aiNode* node;
  glm::dmat4 transform;
  std::vector<uint32_t> particle;
};
// Called while the file is loaded, with Assimp's scene, its mesh uses in the order above and the
// particle count: what a skinned collider reads beyond the surface (colliders/skin.hpp).
using MeshInspector = std::function<void(const aiScene&, std::span<const MeshUse>, size_t particles)>;

// Loads FILE with Assimp. `what` names the scene and key for messages, e.g.
// "scenes/disc.json: cloth.mesh". Throws SceneError (scene.hpp) "<what>: <file>: <problem>"
// for: a missing or unreadable file, a format Assimp cannot read (with Assimp's message), no
// faces, a non-finite coordinate, an edge shared by more than two faces (naming its two
// vertices, 0-based; only with `manifold`, which a cloth needs and a collider does not),
// more than kMaxMeshVertices particles.
PolyMesh load_mesh(const std::filesystem::path& file, const std::string& what, bool manifold = true,
                   const MeshInspector& inspect = {});

}  // namespace clothsim

// Mesh colliders (scene key `mesh`): the file's surface and its signed distance field, loaded
// once per process and shared by the backends, the renderer and --stats (docs/model.md,
// "Mesh colliders").
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>

#include "scene/scene.hpp"
#include "colliders/sdf.hpp"
#include "colliders/skin.hpp"

namespace clothsim {

struct ColliderMesh {
  std::filesystem::path file;
  SurfaceMesh surface;  // metres: the file's triangles scaled, in the collider's own frame
  SdfGrid sdf;          // of `surface`, in the same frame
  double build_seconds = 0;  // building the field (0 when it came from the cache)
  std::filesystem::path cache;  // the cache file read or written; empty: none (a build under a second)
  bool from_cache = false;
  // A skinned collider (mesh.animation): its bones and animation; null for a rigid one. Its
  // surface and field are the bind pose's.
  std::shared_ptr<const Skin> skin;
};

// A build that takes longer than this keeps its field in a cache file in field_cache_folder().
inline constexpr double kSdfCacheSeconds = 1.0;

// The cache folder (docs/model.md, "Mesh colliders"): $XDG_CACHE_HOME/clothsim, else
// ~/.cache/clothsim; empty (no cache) without either, or after disable_field_cache()
// (--no-cache). A cached field carries a checksum; one that fails it is built again, with a note.
std::filesystem::path field_cache_folder();
void disable_field_cache();

// The collider `index` of the scene (`key` its key path for messages, "mesh" or "mesh[1]"):
// loaded and its field built (or read from the cache) on first use, the same object after.
// Throws SceneError "<source>: <key>.<row>: ..." for: a file Assimp cannot read or without
// triangles, a voxel_size whose field would need more than kMaxSdfBytes.
std::shared_ptr<const ColliderMesh> load_collider_mesh(const Scene& scene, size_t index);

// The fields of `meshes` one after the other (the backends' one array; Constants::sdf), the
// same object for the same meshes, so that a live edit does not copy or upload them again.
std::shared_ptr<const std::vector<float>> concatenated_fields(const std::vector<std::shared_ptr<const ColliderMesh>>& meshes);

// The collider's rotation: about the unit rotation_axis by rotation_degrees (right-handed).
glm::dmat3 collider_rotation(const MeshColliderParams& p);

// The collider's vertices in scene coordinates with its origin at `origin` and, for a skinned
// one, posed at scene time t: rotation R v + origin (v the file's vertex scaled), or
// origin + R sum_k w_k (B_k(t) v) over the vertex's bones, in double (export, --stats, drawing).
std::vector<glm::dvec3> posed_positions(const ColliderMesh& mesh, const MeshColliderParams& p, const glm::dvec3& origin,
                                        double t);

// The key path of collider `index` in `scene` ("mesh" for a lone object, else "mesh[i]").
std::string mesh_key(const Scene& scene, size_t index);

// One line per collider loaded by this process, for --stats: triangles, the grid, its memory,
// the build time or the cache it came from.
std::vector<std::string> collider_mesh_report();

}  // namespace clothsim

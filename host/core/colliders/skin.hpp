// Skinned mesh colliders (scene key `mesh.animation`, docs/model.md "Skinned and animated
// colliders"): the file's bones, their weights per vertex and one of its animations, read
// through Assimp, and the bones' matrices at any time. The collider's surface is the file's
// bind pose (its vertices where load_mesh puts them); each substep linear blend skinning
// moves every vertex to sum_k w_k P_k r, r its rest position and P_k the matrices of its (up
// to four) bones at that time (palette_at), on both backends (compute/skin_colliders.comp,
// its CPU twin skin_colliders in host/core/reference).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "cloth/mesh_import.hpp"

namespace clothsim {

// Most bones one vertex follows: the four heaviest of the file's weights, renormalised.
inline constexpr int kBonesPerVertex = 4;

struct Skin {
  // Per vertex of the collider's surface: its bones (palette entries) and their weights,
  // summing to 1 (an unused slot has weight 0 and bone 0).
  std::vector<glm::uvec4> bones;
  std::vector<glm::dvec4> weights;
  // The palette: entry j moves a vertex by node palette_node[j]'s transform at time t times
  // palette_bind[j] (the bone's offset matrix times the inverse of its mesh's node transform,
  // so that at the bind pose every entry is the identity on the rest positions). A mesh with no
  // bones follows its own node (an entry whose bind is the inverse of the node's transform).
  std::vector<int> palette_node;
  std::vector<glm::dmat4> palette_bind;
  // The node tree, parents before children: the static local transforms, and per node its
  // animation channel (-1: none, the node keeps its static transform).
  std::vector<int> parent;
  std::vector<glm::dmat4> local;
  std::vector<int> channel;
  struct Channel {
    std::vector<std::pair<double, glm::dvec3>> positions, scalings;  // (tick, value)
    std::vector<std::pair<double, glm::dquat>> rotations;
  };
  std::vector<Channel> channels;
  // A point cache instead of bones (mesh.point_cache, mesh.sequence): every vertex's position in
  // each frame, in the file's units, frames_per_second apart; palette entry v carries vertex v
  // from its rest position there (bones[v] = v). Empty for a skeleton.
  std::vector<std::vector<glm::dvec3>> frames;
  std::vector<glm::dvec3> rest;  // the file's vertices (its units), which the frames move
  std::string animation;  // its name in the file ("" when it has none)
  double ticks_per_second = 25, duration_ticks = 0;
  double time_scale = 1;
  bool loop = true;

  double duration_seconds() const { return duration_ticks / ticks_per_second; }
  // The animation's tick at scene time t: t time_scale ticks_per_second, wrapped into
  // [0, duration) when looping, else held at its ends.
  double tick_at(double seconds) const;
  // Every palette entry's matrix at scene time t, in the file's units (before the collider's
  // scale, rotation and origin).
  std::vector<glm::dmat4> palette_at(double seconds) const;
};

// A point cache as a skin over `rest` (the collider file's vertices, its units): a PC2 file's
// samples or an OBJ sequence (every .obj of `folder`, in name order, each one frame), played at
// `fps` frames a second. Throws SceneError "<what>: ..." for a cache that cannot be read, has
// fewer than one frame, or whose vertex count is not the mesh's.
Skin read_point_cache(const std::vector<glm::dvec3>& rest, const std::filesystem::path& pc2, double fps,
                      const std::string& what);
Skin read_obj_sequence(const std::vector<glm::dvec3>& rest, const std::filesystem::path& folder, double fps,
                       const std::string& what);

// Reads the skin of a file being loaded (load_mesh's inspector): `animation` is a name of one
// of its animations or an index ("0"). Throws SceneError "<what>: ..." for a file without
// animations, an animation it does not have (naming those it has), bone weights on a vertex
// that does not exist, an animation key that is not finite.
Skin read_skin(const aiScene& scene, std::span<const MeshUse> uses, size_t vertices, const std::string& animation,
               const std::string& what);

}  // namespace clothsim

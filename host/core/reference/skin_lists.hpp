// The skinned mesh colliders' parts of the reference's constants (reference.hpp), fixed over a
// run: their timelines (what the host evaluates per substep) and their lists (what the passes
// read). docs/model.md, "Skinned and animated colliders".
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec4.hpp>

namespace clothsim {

struct Skin;

// A skinned mesh collider's timeline (reference_skinning.cpp): its bones' palette entries
// palette_first.. in Control::palette, and how its file's frame is placed in the scene.
struct SkinnedTimeline {
  std::shared_ptr<const Skin> skin;
  size_t mesh = 0;           // its index among the mesh colliders
  uint32_t palette_first = 0;
  double scale = 1;
  glm::dmat3 rotation{1.0};
};

// The skinned mesh colliders' fixed lists (TEXTURE_SKIN_INDICES, TEXTURE_SKIN_WEIGHTS), every
// skinned collider's in turn: per vertex its bones and weights, per triangle its vertices (w its
// super-group), per cluster of at most kClusterTriangles triangles near one another its
// first triangle and count (x, y), per group of at most kGroupClusters clusters its first
// cluster and count, per super-group of at most kSuperGroups groups its first group and count:
// a three-level tree of boxes, refitted every substep, that a mass's search for its nearest
// triangle descends (and predict's test of whether it is near at all).
template <class R> struct SkinLists {
  std::vector<glm::uvec4> bones, triangles, clusters, groups, supers;
  std::vector<glm::vec<4, R>> weights;
};
inline constexpr uint32_t kClusterTriangles = 8;
inline constexpr uint32_t kGroupClusters = 16;
inline constexpr uint32_t kSuperGroups = 8;
// The poses of its animation, besides the bind pose, that the triangles' order keeps compact in
// (order_for_tree in reference_skinning.cpp).
inline constexpr int kTreePoses = 8;

}  // namespace clothsim

// Two parts of the reference's Constants (reference.hpp) that stand on their own: what moves
// with time (Timeline, in double) and each cloth's material (MaterialC, in R).
#pragma once

#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cloth/cloth.hpp"
#include "reference/skin_lists.hpp"
#include "scene/scene.hpp"

namespace clothsim {

// What moves with time, in double: evaluated once per substep by set_substep_time into Control.
struct Timeline {
  std::vector<std::optional<Keyframes>> spheres, planes, meshes;  // by collider, in file order
  std::vector<glm::dvec3> mesh_origins;                   // by mesh collider: its origin without keys
  std::vector<SkinnedTimeline> skins;                     // the skinned mesh colliders
  std::optional<Keyframes> pins;                          // offsets of the pinned masses
  double gust_period = 0;                                 // 0: no gusts
  double sewing_speed = 0;                                // m/s; 0: no seams
  double dt = 0;
  bool moves() const;  // anything above is set
};

// One cloth's material, converted once to R (a scene with several cloths has one each).
template <class R> struct MaterialC {
  R ks, ks_bending;        // N/m: structural and shearing, bending (0.2 ks)
  // N/m: the stiffness fabric's start and fold threshold weigh the inertia against
  // (adaptive_share): ks, or kMaterialStartStiffness for a cloth with a material.
  R start_ks;
  R keep_velocity;         // 1 - damping / 100
  bool enabled[kSpringTypes];  // by SpringType (seams always)
  // A material's membrane moduli (C11, C22 and G in N/m, z the compression ratio: membrane.glsl);
  // 0 without one.
  glm::vec<4, R> moduli{};
  R stiffness(SpringType t) const { return t == SpringType::Bending ? ks_bending : ks; }
};

}  // namespace clothsim

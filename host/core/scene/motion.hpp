// Keyframed motion (scene.hpp: MotionParams) evaluated at a simulated time, in double. The
// host evaluates every motion once per substep and hands both backends the same rounded
// values (reference.hpp: set_substep_time), so no shader interpolates keys.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace clothsim {

// Linear between keys, the first key's value before its time, the last key's after its time.
inline glm::dvec3 interpolate(const Keyframes& keys, double t) {
  if (keys.empty()) return glm::dvec3(0.0);
  if (t <= keys.front().time) return keys.front().value;
  for (size_t k = 1; k < keys.size(); ++k)
    if (t < keys[k].time) {
      const Keyframe &a = keys[k - 1], &b = keys[k];
      const double s = (t - a.time) / (b.time - a.time);
      return a.value + (b.value - a.value) * s;
    }
  return keys.back().value;
}

// A keyed value at time t: its keys' if it has them, else `fixed` (where the scene puts it).
inline glm::dvec3 keyed_at(const std::optional<Keyframes>& keys, const glm::dvec3& fixed, double t) {
  return keys ? interpolate(*keys, t) : fixed;
}
inline glm::dvec3 keyed_at(const std::optional<MotionParams>& motion, const glm::dvec3& fixed, double t) {
  return motion ? interpolate(motion->keyframes, t) : fixed;
}

// Where a collider's origin (a sphere's origin, a plane's point, a mesh's origin) is at time t:
// its motion's keys if it has them, else where the scene puts it.
inline glm::dvec3 collider_origin(const Scene& scene, const ColliderRef& ref, double t) {
  if (ref.kind == 1) return keyed_at(scene.spheres[ref.index].motion, scene.spheres[ref.index].origin, t);
  if (ref.kind == 2) return keyed_at(scene.planes[ref.index].motion, scene.planes[ref.index].point, t);
  return keyed_at(scene.meshes[ref.index].motion, scene.meshes[ref.index].origin, t);
}

// The fractional part of t / period, in [0, 1): the gusts' phase in time, kept small so that
// float resolution does not degrade over a long run.
inline double gust_phase(double t, double period) {
  const double q = t / period;
  return q - std::floor(q);
}

}  // namespace clothsim

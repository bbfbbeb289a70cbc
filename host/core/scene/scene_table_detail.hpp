// What the scene parameter table's files share (scene_table.cpp, scene_table_mesh.cpp): the
// viewer's widgets, the normalising rules of vectors read, and the friction row.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/param_table.hpp"

namespace clothsim::table_detail {

constexpr Widget drag(float speed, double lo, double hi, const char* format) {
  return {.style = Widget::Drag, .speed = speed, .lo = lo, .hi = hi, .format = format};
}
inline constexpr Widget kCheckbox{.style = Widget::Checkbox};
inline constexpr Widget kReadOnly{.style = Widget::ReadOnly};

// Unit length, or false for [0, 0, 0].
inline bool normalise(glm::dvec3& n) {
  // Scale by the largest component first: |n| of a finite n such as [1e200, 0, 0] overflows.
  const double m = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
  if (m == 0) return false;
  // A normal that is already unit to rounding is kept as written, so that normalising is
  // idempotent and scene_to_json's output loads back to the same normal, bit for bit.
  const double len2 = n.x * n.x + n.y * n.y + n.z * n.z;
  if (std::abs(len2 - 1) > 4 * std::numeric_limits<double>::epsilon()) {
    n /= m;
    n /= std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  }
  return true;
}

inline const char* normalise_normal(glm::dvec3& n) {
  return normalise(n) ? nullptr : "expected a non-zero normal vector, got [0, 0, 0]";
}
inline const char* normalise_axis(glm::dvec3& n) {
  return normalise(n) ? nullptr : "expected a non-zero rotation axis, got [0, 0, 0]";
}

inline const ParamInfo kFriction{.key = "friction", .required = true, .lo = 0, .hi = 1,
                          .expected = "a friction coefficient in [0, 1]",
                          .meaning = "classic: the CS184 blend, 0 a touching mass keeps its motion, 1 it "
                                     "sticks; fabric: Coulomb's mu, a cloth holds on a slope while tan(angle) <= mu"};

}  // namespace clothsim::table_detail

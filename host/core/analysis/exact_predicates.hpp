// The parts of the exact orientation predicates (exact_predicates.cpp) that the triangle pair
// test (intersections.cpp) uses besides orient3d and orient2d (intersections.hpp): Shewchuk's
// filtered orient3d, which says when it cannot tell, and the exact one to ask then, so that the
// pair test can first try a cheap separation for nearly coplanar triangles.
#pragma once

#include <glm/vec3.hpp>

namespace clothsim::exact::detail {

inline constexpr double kEps = 0x1p-53;  // half an ulp of 1: the unit roundoff
inline constexpr int kUncertain = 2;     // orient3d_filtered's "cannot tell"

// orient3d in double with Shewchuk's static error bound: the exact sign, or kUncertain.
int orient3d_filtered(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d);
// The exact sign of Shewchuk's orient3d(a, b, c, d) = det[a - d, b - d, c - d] (the negative
// of orient3d's).
int orient3d_exact(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d);

}  // namespace clothsim::exact::detail

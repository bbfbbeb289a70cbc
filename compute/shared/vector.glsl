// The vector helpers every formula uses, summed in one fixed order (x, then y, then z) so that
// the reference and llvmpipe round alike (GLSL's own length and dot may sum otherwise). Included
// by compute/common.glsl (every shader), by the other files of compute/shared/ and by
// host/core/reference/reference.hpp.
#ifndef CLOTHSIM_SHARED_VECTOR_GLSL
#define CLOTHSIM_SHARED_VECTOR_GLSL

#include "dialect.glsl"

SHARED_BEGIN

SHARED_FN REAL length3(VEC3 v) {
  PRECISE REAL s = v.x * v.x + v.y * v.y + v.z * v.z;
  return sqrt(s);
}

SHARED_FN REAL dot3(VEC3 a, VEC3 b) {
  PRECISE REAL s = a.x * b.x + a.y * b.y + a.z * b.z;
  return s;
}

// The cross product u x v, written out (twice the area times the normal of a triangle u, v).
SHARED_FN VEC3 cross3(VEC3 u, VEC3 v) {
  PRECISE VEC3 c = VEC3(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
  return c;
}

// v / |v|, or up where v is 0 (a normal with no direction).
SHARED_FN VEC3 unit_or_up(VEC3 v) {
  REAL len = length3(v);
  PRECISE REAL inv = REAL(1) / len;
  PRECISE VEC3 unit = v * inv;
  return len > REAL(0) ? unit : VEC3(REAL(0), REAL(1), REAL(0));
}

SHARED_END

#endif

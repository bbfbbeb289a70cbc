// A file of compute/shared/ gone wrong, one breach a line (tests/tools/check_shared_dialect.py
// must find exactly 10): the test that the check finds what it is meant to.
#ifndef CLOTHSIM_SHARED_DIALECT_BAD_GLSL
#define CLOTHSIM_SHARED_DIALECT_BAD_GLSL

#include "../../compute/shared/vector.glsl"

SHARED_BEGIN

SHARED_FN REAL half_of(REAL x) { return x * 0.5; }
SHARED_FN float twice(REAL x) { return x * REAL(2); }
SHARED_FN void bump(inout VEC3 v) { v = v + VEC3(REAL(1)); }
SHARED_FN REAL first(VEC3 v) { REAL a[2]; return v.x; }
SHARED_FN VEC3 flat(VEC4 v) { return v.xyz; }
SHARED_FN REAL len(VEC3 v) { return length(v); }
REAL unmarked(REAL x) { return x; }
SHARED_FN REAL pick(int k, REAL x) { switch (k) { default: return x; } }
SHARED_FN REAL nudge(REAL a) { PRECISE REAL t = a + REAL(1) * 1e-3f; return t; }
SHARED_FN REAL third(int k) { return REAL(k % 3); }

#ifdef __cplusplus
// C++ only: not the shared part, so none of this counts.
inline float cpp_only(float x) { return x * 0.5f; }
#endif

SHARED_END

#endif

// The divergence guard's helpers, shared by check_divergence and keep_last_good; their
// formulas are compute/shared/divergence.glsl's.
#ifndef CLOTHSIM_DIVERGENCE_GLSL
#define CLOTHSIM_DIVERGENCE_GLSL

#include "shared/divergence.glsl"

// Tested on the bits, not with isnan/isinf, which a compiler may assume away.
bool all_finite(vec3 x) {
  uvec3 exponent = floatBitsToUint(x) & uvec3(0x7f800000u);
  return all(notEqual(exponent, uvec3(0x7f800000u)));
}

// A frame passes when it is finite and reaches at most `limit` from `centre` on every axis.
bool within_limits(FrameBounds b, vec3 centre, float limit) {
  if (b.lo.w != 0u) return false;
  vec3 hi = vec3(from_ordered_bits(b.hi.x), from_ordered_bits(b.hi.y), from_ordered_bits(b.hi.z));
  vec3 lo = vec3(from_ordered_bits(b.lo.x), from_ordered_bits(b.lo.y), from_ordered_bits(b.lo.z));
  return bounds_within(lo, hi, centre, limit);
}

#endif

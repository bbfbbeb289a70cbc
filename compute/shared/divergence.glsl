// The divergence guard's formulas (docs/model.md, "The divergence guard"): a float's ordered
// bits, through which check_divergence reduces a frame's bounds with atomicMin/atomicMax, and
// the test of a frame's bounds against its limit. Included by compute/divergence.glsl (the
// passes check_divergence and keep_last_good), host/gpu/gpu_divergence.cpp (decoding what
// they wrote) and host/core/analysis/divergence.cpp (the CPU backend's guard).
#ifndef CLOTHSIM_SHARED_DIVERGENCE_GLSL
#define CLOTHSIM_SHARED_DIVERGENCE_GLSL

#include "dialect.glsl"

SHARED_BEGIN

// Float bits as a uint whose unsigned order is the float order: negative floats have every
// bit flipped, the others their sign bit set.
SHARED uint ordered_bits(F32 f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

SHARED F32 from_ordered_bits(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u); }

// A frame of finite bounds lo..hi passes when it reaches at most `limit` from `centre` on
// every axis.
SHARED_FN bool bounds_within(VEC3 lo, VEC3 hi, VEC3 centre, REAL limit) {
  PRECISE VEC3 above = hi - centre;
  PRECISE VEC3 below = centre - lo;
  return !(above.x > limit || above.y > limit || above.z > limit || below.x > limit || below.y > limit ||
           below.z > limit);
}

SHARED_END

#endif

// The divergence guard's helpers, shared by check_divergence and keep_last_good. The C++
// twins are in host/core/analysis/divergence.cpp (within_limits) and host/gpu/gpu_divergence.cpp
// (ordered bits).
#ifndef CLOTHSIM_DIVERGENCE_GLSL
#define CLOTHSIM_DIVERGENCE_GLSL

// Float bits as a uint whose unsigned order is the float order: negative floats have every
// bit flipped, the others their sign bit set. Then atomicMin/atomicMax on uints reduce floats.
uint ordered_bits(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

float from_ordered_bits(uint u) {
  return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}

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
  precise vec3 above = hi - centre;
  precise vec3 below = centre - lo;
  return !any(greaterThan(above, vec3(limit))) && !any(greaterThan(below, vec3(limit)));
}

#endif

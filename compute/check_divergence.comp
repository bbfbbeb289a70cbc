// Reads positions; writes the frame's FrameBounds (bounding box of the finite positions, and
// a NaN/Inf flag), which the host set to the empty box beforehand. One invocation per
// particle: a tree reduction in shared memory, then one atomic per value and workgroup.
#include "layout.glsl"
#include "divergence.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_CHECKED_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_FRAME_BOUNDS) buffer Bounds { FrameBounds bounds; };

uniform uint u_count;  // particles

shared vec3 s_lo[WORKGROUP_SIZE];
shared vec3 s_hi[WORKGROUP_SIZE];
shared uint s_not_finite;

void main() {
  uint i = gl_GlobalInvocationID.x, t = gl_LocalInvocationID.x;
  if (t == 0u) s_not_finite = 0u;
  barrier();
  // The empty box (+Inf, -Inf) for particles past the end and for non-finite ones.
  vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
  if (i < u_count) {
    vec3 x = pos[i].xyz;
    if (all_finite(x)) {
      lo = x;
      hi = x;
    } else {
      atomicOr(s_not_finite, 1u);
    }
  }
  s_lo[t] = lo;
  s_hi[t] = hi;
  for (uint d = WORKGROUP_SIZE / 2; d > 0u; d >>= 1) {
    barrier();
    if (t < d) {
      s_lo[t] = min(s_lo[t], s_lo[t + d]);
      s_hi[t] = max(s_hi[t], s_hi[t + d]);
    }
  }
  barrier();
  if (t != 0u) return;
  atomicMin(bounds.lo.x, ordered_bits(s_lo[0].x));
  atomicMin(bounds.lo.y, ordered_bits(s_lo[0].y));
  atomicMin(bounds.lo.z, ordered_bits(s_lo[0].z));
  atomicMax(bounds.hi.x, ordered_bits(s_hi[0].x));
  atomicMax(bounds.hi.y, ordered_bits(s_hi[0].y));
  atomicMax(bounds.hi.z, ordered_bits(s_hi[0].z));
  if (s_not_finite != 0u) atomicOr(bounds.lo.w, 1u);
}

// Reads the residuals of the next finer level (through their view); writes the coarse right-hand
// sides, the level's residuals (the same: its correction starts at zero) and zeroes its
// corrections. One invocation per coarse vertex of the level (vertices [u_first, u_first +
// u_count)): the weighted sum of its children's residual forces and masses. The CPU twin is
// restrict_residuals in host/core/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_RESIDUALS) writeonly buffer Residuals { vec4 residual[]; };
layout(std430, binding = BINDING_MG_RHS) writeonly buffer Rhs { vec4 rhs[]; };
layout(std430, binding = BINDING_MG_CORR) writeonly buffer Corrections { vec4 corr[]; };

// Coarse vertex g (its row v) in a fold: a coarse spring shorter than FOLDED_CHORD of its rest
// length (folded in host/core/reference_multigrid.cpp).
bool folded(uint g, uvec4 v) {
  vec3 p = position_of(int(v.x)).xyz;
  uint last = mg_vertex(g + 1u).w;
  for (uint k = v.w; k < last; ++k) {
    uvec4 s = mg_entry(k);  // y rest bits, w the other end's particle
    precise float shortest = FOLDED_CHORD * uintBitsToFloat(s.y);
    if (length3(position_of(int(s.w)).xyz - p) < shortest) return true;
  }
  return false;
}

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  uint g = u_first + gl_GlobalInvocationID.x;
  uvec4 v = mg_vertex(g);
  corr[g] = vec4(0.0);
  // Pinned, held, held by a collider, or in a fold: fixed in the coarse problem (w -1 says so).
  vec4 p = position_of(int(v.x));
  precise vec3 start = p.xyz + offset_of(int(v.x));
  if (p.w == 0.0 ||
      (has_colliders() && touches_colliders(start)) ||
      folded(g, v)) {
    rhs[g] = vec4(0.0, 0.0, 0.0, -1.0);
    residual[particle_count() + g] = vec4(0.0);
    return;
  }
  uint first = v.y, last = mg_vertex(g + 1u).y;
  precise vec4 b = vec4(0.0);
  for (uint k = first; k < last; ++k) {
    uvec4 c = mg_entry(k);  // x the child's residual, y its weight's bits
    b = b + residual_of(c.x) * uintBitsToFloat(c.y);
  }
  rhs[g] = b;  // xyz the force, w the mass the vertex stands for
  // The next level restricts this one's residual: with the correction at zero, b itself. (A
  // child is on the finer level, so no invocation of this dispatch reads what another writes.)
  residual[particle_count() + g] = b;
}

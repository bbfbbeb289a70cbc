// Reads the residuals of the next finer level; writes the coarse right-hand sides, the level's
// residuals (the same: its correction starts at zero) and zeroes its corrections. One
// invocation per coarse vertex of the level (vertices [u_first, u_first + u_count)): the
// weighted sum of its children's residual forces and masses.
// The CPU twin is restrict_residuals in host/core/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_RESIDUALS) buffer Residuals { vec4 residual[]; };
layout(std430, binding = BINDING_MG_RHS) writeonly buffer Rhs { vec4 rhs[]; };
layout(std430, binding = BINDING_MG_CORR) writeonly buffer Corrections { vec4 corr[]; };

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  uint g = u_first + gl_GlobalInvocationID.x;
  uint first = mg_vertex(g).y, last = mg_vertex(g + 1u).y;
  precise vec4 b = vec4(0.0);
  for (uint k = first; k < last; ++k) {
    uvec4 c = mg_entry(k);  // x the child's residual, y its weight's bits
    b = b + residual[c.x] * uintBitsToFloat(c.y);
  }
  rhs[g] = b;  // xyz the force, w the mass the vertex stands for
  corr[g] = vec4(0.0);
  // The next level restricts this one's residual: with the correction at zero, b itself. (A
  // child is on the finer level, so no invocation of this dispatch reads what another writes.)
  residual[particle_count() + g] = b;
}

// Reads the residuals of the next finer level (through their view); writes the coarse right-hand
// sides, the level's residuals (the same: its correction starts at zero) and zeroes its
// corrections. One invocation per coarse vertex of the level (vertices [u_first, u_first +
// u_count)): restrict_vertex (coarse_levels.glsl), the weighted sum of its children's residual
// forces and masses. The CPU twin is restrict_residuals in host/core/reference/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_RESIDUALS) writeonly buffer Residuals { vec4 residual[]; };
layout(std430, binding = BINDING_MG_RHS) writeonly buffer Rhs { vec4 rhs[]; };
layout(std430, binding = BINDING_MG_CORR) writeonly buffer Corrections { vec4 corr[]; };
#include "coarse_levels.glsl"

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  restrict_vertex(u_first + gl_GlobalInvocationID.x);
}

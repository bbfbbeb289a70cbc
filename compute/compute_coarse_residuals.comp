// Reads positions, the right-hand sides and the corrections (through their view); writes the
// coarse residuals of one level. One invocation per coarse vertex of the level (vertices
// [u_first, u_first + u_count)): b - A e, w the mass it stands for, restricted to the next
// level by restrict_residuals. The CPU twin is compute_coarse_residuals in
// host/core/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_RHS) readonly buffer Rhs { vec4 rhs[]; };
layout(std430, binding = BINDING_MG_RESIDUALS) writeonly buffer Residuals { vec4 residual[]; };

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  uint g = u_first + gl_GlobalInvocationID.x;
  uvec4 v = mg_vertex(g);
  uint slot = particle_count() + g;
  if (position_of(int(v.x)).w == 0.0) {
    residual[slot] = vec4(0.0);
    return;
  }
  vec4 b = rhs[g];
  Sym3 diag;
  residual[slot] = vec4(coarse_residual(g, v, b, diag), b.w);
}

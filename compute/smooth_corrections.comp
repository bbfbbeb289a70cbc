// Reads positions, the right-hand sides and the corrections (through their views); writes the
// corrections of one colour of one level. One invocation per coarse vertex of the colour
// (order entries [u_first, u_first + u_count)): a Gauss-Seidel step of the linear coarse
// problem on the vertex's 3x3 block; no two vertices of a colour share a coarse spring, so
// the writes never race with a read. The CPU twin is smooth_corrections in
// host/core/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_CORR) writeonly buffer Corrections { vec4 corr[]; };

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  uint g = texelFetch(mg_order_view, int(u_first + gl_GlobalInvocationID.x)).x;
  uvec4 v = mg_vertex(g);
  vec4 b = rhs_of(g);
  if (b.w < 0.0) return;  // a fixed vertex does not move (restrict_residuals)
  Sym3 diag;
  vec3 r = coarse_residual(g, v, b, diag);
  vec3 step;
  if (solve3(diag, r, step)) {
    precise vec3 e = texelFetch(mg_corr_view, int(g)).xyz + step;
    corr[g] = vec4(e, 0.0);
  }
}

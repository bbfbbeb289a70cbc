// Reads positions, the right-hand sides and the corrections (through their views); writes the
// corrections of one colour of one level. One invocation per coarse vertex of the colour
// (order entries [u_first, u_first + u_count)): smooth_vertex (coarse_levels.glsl), a
// Gauss-Seidel step of the linear coarse problem on the vertex's 3x3 block. The CPU twin is
// smooth_corrections in host/core/reference/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
// coarse_levels.glsl's other steps write these; this pass only reads them, through their views.
layout(std430, binding = BINDING_MG_RESIDUALS) writeonly buffer Residuals { vec4 residual[]; };
layout(std430, binding = BINDING_MG_RHS) writeonly buffer Rhs { vec4 rhs[]; };
layout(std430, binding = BINDING_MG_CORR) writeonly buffer Corrections { vec4 corr[]; };
#include "coarse_levels.glsl"

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  smooth_vertex(texelFetch(mg_order_view, int(u_first + gl_GlobalInvocationID.x)).x);
}

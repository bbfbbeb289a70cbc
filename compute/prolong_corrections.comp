// Reads the corrections (through their view: the coarser level's); writes the corrections of
// one level. One invocation per coarse vertex of the level (vertices [u_first, u_first +
// u_count)): prolong_vertex (coarse_levels.glsl), its parents' corrections, weighted, added to
// its own. The CPU twin is prolong_corrections in host/core/reference/reference_multigrid.cpp.
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
  prolong_vertex(u_first + gl_GlobalInvocationID.x);
}

// Reads the corrections (through their view: the coarser level's); writes the corrections of
// one level. One invocation per coarse vertex of the level (vertices [u_first, u_first +
// u_count)): its parents' corrections, weighted, added to its own. The CPU twin is
// prolong_corrections in host/core/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_CORR) writeonly buffer Corrections { vec4 corr[]; };

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  uint g = u_first + gl_GlobalInvocationID.x;
  uvec4 v = mg_vertex(g);
  if (rhs_of(g).w < 0.0) return;  // a fixed vertex does not move (restrict_residuals)
  uint last = mg_vertex(g + 1u).z;
  precise vec3 e = vec3(0.0);
  for (uint k = v.z; k < last; ++k) {
    uvec4 p = mg_entry(k);  // x the parent, y its weight's bits
    e = e + texelFetch(mg_corr_view, int(p.x)).xyz * uintBitsToFloat(p.y);
  }
  precise vec3 sum = texelFetch(mg_corr_view, int(g)).xyz + e;
  corr[g] = vec4(sum, 0.0);
}

// Reads positions; writes (increments) the per-bucket particle counts. One invocation per
// particle. The only pass with atomics: the totals do not depend on their order.
#include "layout.glsl"
#include "common.glsl"
#include "spatial_hash.glsl"
#include "particle_views.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_CELL_COUNT) buffer Counts { uint cell_count[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  atomicAdd(cell_count[hash_cell(cell_of(position_of(int(i)).xyz))], 1u);
}

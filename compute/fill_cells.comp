// Reads positions and bucket starts; writes particle ids into cell order, using the counts
// (zeroed beforehand) as per-bucket cursors. One invocation per particle. The order within a
// bucket depends on thread timing here; sort_cells makes it ascending afterwards.
#include "layout.glsl"
#include "common.glsl"
#include "spatial_hash.glsl"
#include "particle_views.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_CELL_COUNT) buffer Cursors { uint cursor[]; };
layout(std430, binding = BINDING_CELL_START) readonly buffer Starts { uint cell_start[]; };
layout(std430, binding = BINDING_CELL_ENTRIES) writeonly buffer Entries { uint entries[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  uint b = hash_cell(cell_of(position_of(int(i)).xyz));
  entries[cell_start[b] + atomicAdd(cursor[b], 1u)] = i;
}

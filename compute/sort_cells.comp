// Reads bucket starts and positions; sorts the particle ids of each bucket ascending in place
// and writes the positions in that order (collide_self reads a candidate's position without
// going through its id). One invocation per bucket (buckets hold a handful of ids, so
// insertion sort is the right tool). The ascending order makes every later sum independent
// of the order fill_cells happened to write in.
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_CELL_START) readonly buffer Starts { uint cell_start[]; };
layout(std430, binding = BINDING_CELL_ENTRIES) buffer Entries { uint entries[]; };
layout(std430, binding = BINDING_SORTED_POSITIONS) writeonly buffer Sorted { vec4 sorted_pos[]; };

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= params.table_size) return;
  uint first = cell_start[b], last = cell_start[b + 1u];
  for (uint k = first + 1u; k < last; ++k) {
    uint id = entries[k];
    uint m = k;
    while (m > first && entries[m - 1u] > id) {
      entries[m] = entries[m - 1u];
      --m;
    }
    entries[m] = id;
  }
  for (uint k = first; k < last; ++k) sorted_pos[k] = position_of(int(entries[k]));
}

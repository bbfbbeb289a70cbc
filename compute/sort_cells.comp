// Reads bucket starts; sorts the particle ids of each bucket ascending in place. One
// invocation per bucket (buckets hold a handful of ids, so insertion sort is the right tool).
// This makes every later sum independent of the order fill_cells happened to write in.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_CELL_START) readonly buffer Starts { uint cell_start[]; };
layout(std430, binding = BINDING_CELL_ENTRIES) buffer Entries { uint entries[]; };

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= params.grid.w) return;
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
}

// Reads and writes one block of SCAN_BLOCK = 2 * WORKGROUP_SIZE uints in place, turning it
// into its exclusive prefix sum, and writes the block's total to the sums array. One
// workgroup per block, two elements per invocation (Blelloch's work-efficient scan in shared
// memory). Larger arrays scan the sums recursively and add them back (add_scan_offsets).
#include "layout.glsl"

#define SCAN_BLOCK (2 * WORKGROUP_SIZE)

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_SCAN_DATA) buffer Data { uint data[]; };
layout(std430, binding = BINDING_SCAN_SUMS) writeonly buffer Sums { uint sums[]; };

uniform uint u_count;  // elements in data

shared uint tile[SCAN_BLOCK];

void main() {
  uint t = gl_LocalInvocationID.x;
  uint base = gl_WorkGroupID.x * SCAN_BLOCK;
  uint a = base + 2u * t, b = a + 1u;
  tile[2u * t] = a < u_count ? data[a] : 0u;
  tile[2u * t + 1u] = b < u_count ? data[b] : 0u;

  // Up-sweep: build partial sums in a balanced tree.
  uint offset = 1u;
  for (uint d = SCAN_BLOCK >> 1; d > 0u; d >>= 1) {
    barrier();
    if (t < d) {
      uint ai = offset * (2u * t + 1u) - 1u, bi = offset * (2u * t + 2u) - 1u;
      tile[bi] += tile[ai];
    }
    offset <<= 1;
  }
  if (t == 0u) {
    sums[gl_WorkGroupID.x] = tile[SCAN_BLOCK - 1];
    tile[SCAN_BLOCK - 1] = 0u;
  }
  // Down-sweep: push prefixes back down the tree.
  for (uint d = 1u; d < SCAN_BLOCK; d <<= 1) {
    offset >>= 1;
    barrier();
    if (t < d) {
      uint ai = offset * (2u * t + 1u) - 1u, bi = offset * (2u * t + 2u) - 1u;
      uint left = tile[ai];
      tile[ai] = tile[bi];
      tile[bi] += left;
    }
  }
  barrier();
  if (a < u_count) data[a] = tile[2u * t];
  if (b < u_count) data[b] = tile[2u * t + 1u];
}

// Reads and writes one chunk of SCAN_CHUNK consecutive uints in place, turning it into its
// exclusive prefix sum, and writes the chunk's total to the sums array. One invocation per
// chunk, serial within it: no shared memory and no barriers. (A Blelloch tree in shared
// memory needs 2 log2(block) workgroup barriers; on llvmpipe each one suspends and resumes
// every invocation, which cost ~90 ns per element. Serial chunks cost a load and a store per
// element, and on a GPU a chunk is one or two cache lines read by one thread.) Larger arrays
// scan the chunk totals recursively and add them back (add_scan_offsets).
#include "layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_SCAN_DATA) buffer Data { uint data[]; };
layout(std430, binding = BINDING_SCAN_SUMS) writeonly buffer Sums { uint sums[]; };

uniform uint u_count;  // elements in data

void main() {
  uint chunk = gl_GlobalInvocationID.x;
  uint first = chunk * uint(SCAN_CHUNK);
  if (first >= u_count) return;
  uint last = min(first + uint(SCAN_CHUNK), u_count);
  uint running = 0u;
  for (uint k = first; k < last; ++k) {
    uint v = data[k];
    data[k] = running;
    running += v;
  }
  sums[chunk] = running;
}

// Reads the scanned chunk totals; adds each chunk's prefix to every element of the chunk in
// place. One invocation per element (the second half of a multi-level scan).
#include "layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_SCAN_DATA) buffer Data { uint data[]; };
layout(std430, binding = BINDING_SCAN_SUMS) readonly buffer Sums { uint sums[]; };

uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  data[i] += sums[i / uint(SCAN_CHUNK)];
}

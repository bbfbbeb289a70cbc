// Reads positions and the frame's FrameBounds (from check_divergence); writes the kept copy of
// the positions and its header, as long as every frame so far has passed. One invocation per
// particle. After a failure nothing is copied again, so the copy is the frame before it.
#include "layout.glsl"
#include "divergence.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_CHECKED_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_FRAME_BOUNDS) readonly buffer Bounds { FrameBounds bounds; };
layout(std430, binding = BINDING_LAST_GOOD) buffer LastGood {
  LastGoodHeader header;
  vec4 kept[];
};

uniform uint u_count;   // particles
uniform uint u_frame;   // the frame being checked
uniform vec3 u_centre;  // where the cloth started
uniform float u_limit;  // how far from there it may reach, per axis

void main() {
  uint i = gl_GlobalInvocationID.x;
  // Invocation 0 may set the flag while others read it: they have failed this frame as well.
  if (header.state.x != 0u) return;
  if (!within_limits(bounds, u_centre, u_limit)) {
    if (i == 0u) header.state.x = 1u;
    return;
  }
  if (i < u_count) kept[i] = pos[i];
  if (i == 0u) header.state.y = u_frame;
}

// Reads positions and rest lengths; writes forces. One invocation per particle: it gathers
// gravity plus its own (up to twelve) springs in a fixed order, so no atomics are needed.
#include "layout.glsl"
#include "common.glsl"
#include "spring_grid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_REST) readonly buffer Rest { RestLengths rest[]; };
layout(std430, binding = BINDING_FORCES) writeonly buffer Forces { vec4 force[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  ivec2 c = grid_coord(i);
  vec3 xi = pos[i].xyz;
  precise vec3 f = params.gravity_mass.xyz * params.gravity_mass.w;
  // Same order as kGatherOrder: per direction, the spring stored here, then the one stored
  // at the neighbour behind.
  for (int k = 0; k < 2 * NUM_DIRECTIONS; ++k) {
    int direction = k >> 1;
    int sign = (k & 1) == 0 ? 1 : -1;
    ivec2 cj = c + sign * DIRECTION_OFFSET[direction];
    if (!in_grid(cj) || !spring_enabled(direction)) continue;
    int j = grid_index(cj);
    float rest_length = rest_component(rest[sign > 0 ? int(i) : j], direction);
    float k_spring = DIRECTION_TYPE[direction] == 2u ? params.springs.y : params.springs.x;
    vec3 e = pos[j].xyz - xi;
    float len = length3(e);
    if (len > 0.0) {
      precise float inv = 1.0 / len;
      precise float magnitude = k_spring * (len - rest_length) * inv;
      f = f + e * magnitude;
    }
  }
  force[i] = vec4(f, 0.0);
}

// Reads and writes positions in place. Dispatched once per colour; one invocation per
// particle, which handles the spring of this colour stored at it (if any). No two springs of
// a colour share a particle, so the writes never race (Provot 1995 length limit).
#include "layout.glsl"
#include "common.glsl"
#include "spring_grid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_REST) readonly buffer Rest { RestLengths rest[]; };

uniform int u_colour;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  int direction = u_colour >> 1;
  ivec2 c = grid_coord(i);
  ivec2 cj = c + DIRECTION_OFFSET[direction];
  if (spring_colour(direction, c) != u_colour || !in_grid(cj) || !spring_enabled(direction)) return;
  int j = grid_index(cj);
  vec4 pi = pos[i], pj = pos[j];
  precise float wsum = pi.w + pj.w;
  if (wsum == 0.0) return;  // both ends pinned
  vec3 e = pj.xyz - pi.xyz;
  float len = length3(e);
  precise float limit = params.constraint.x * rest_component(rest[i], direction);
  if (!(len > limit)) return;
  precise float excess = (len - limit) * (1.0 / len);
  precise vec3 corr = e * excess;
  precise float inv_wsum = 1.0 / wsum;
  precise vec3 xi = pi.xyz + corr * (pi.w * inv_wsum);
  precise vec3 xj = pj.xyz - corr * (pj.w * inv_wsum);
  pos[i] = vec4(xi, pi.w);
  pos[j] = vec4(xj, pj.w);
}

// Reads (through the view) and writes positions in place. Dispatched once per colour over that colour's span
// (colour_span in host/core/spring_grid.hpp): one invocation per spring of the colour, and
// no two springs of a colour share a particle, so the writes never race (Provot 1995).
#include "layout.glsl"
#include "common.glsl"
#include "spring_grid.glsl"
#include "particle_views.glsl"

layout(local_size_x = GRID_WORKGROUP_X, local_size_y = GRID_WORKGROUP_Y) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };

uniform int u_colour;
uniform ivec4 u_span_x;  // AxisSpan: first, period, shift, count
uniform ivec4 u_span_y;

int span_coord(ivec4 s, int k) { return s.x + s.y * (k >> s.z) + (k & ((1 << s.z) - 1)); }

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= u_span_x.w || k.y >= u_span_y.w) return;
  int direction = u_colour >> 1;
  ivec2 c = ivec2(span_coord(u_span_x, k.x), span_coord(u_span_y, k.y));
  int i = grid_index(c);
  int j = grid_index(c + DIRECTION_OFFSET[direction]);
  vec4 pi = position_of(i), pj = position_of(j);
  precise float wsum = pi.w + pj.w;
  if (wsum == 0.0) return;  // both ends pinned
  vec3 e = pj.xyz - pi.xyz;
  float len = length3(e);
  precise float limit = params.constraint.x * rest_length(i, direction);
  if (!(len > limit)) return;
  precise float excess = (len - limit) * (1.0 / len);
  precise vec3 corr = e * excess;
  precise float inv_wsum = 1.0 / wsum;
  precise vec3 xi = pi.xyz + corr * (pi.w * inv_wsum);
  precise vec3 xj = pj.xyz - corr * (pj.w * inv_wsum);
  pos[i].xyz = xi;
  pos[j].xyz = xj;
}

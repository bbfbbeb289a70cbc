// Reads (through the views) and writes positions and displacements in place. Dispatched once per colour over that colour's span
// (colour_span in host/core/spring_grid.hpp): one invocation per spring of the colour, and
// no two springs of a colour share a particle, so the writes never race (Provot 1995).
#include "layout.glsl"
#include "common.glsl"
#include "spring_grid.glsl"
#include "particle_views.glsl"

layout(local_size_x = GRID_WORKGROUP_X, local_size_y = GRID_WORKGROUP_Y) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };

uniform int u_colour;
// The span of every colour (colour_span in host/core/spring_grid.hpp), set once for the grid:
// u_spans[2 c] along x, u_spans[2 c + 1] along y, each an AxisSpan (first, period, shift, count).
uniform ivec4 u_spans[2 * NUM_COLOURS];

int span_coord(ivec4 s, int k) { return s.x + s.y * (k >> s.z) + (k & ((1 << s.z) - 1)); }

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  ivec4 span_x = u_spans[2 * u_colour], span_y = u_spans[2 * u_colour + 1];
  if (k.x >= span_x.w || k.y >= span_y.w) return;
  int direction = u_colour >> 1;
  ivec2 c = ivec2(span_coord(span_x, k.x), span_coord(span_y, k.y));
  int i = grid_index(c);
  int j = grid_index(c + direction_offset(direction));
  vec4 pi = position_of(i), pj = position_of(j);
  precise float wsum = pi.w + pj.w;
  if (wsum == 0.0) return;  // both ends pinned
  vec3 e = pj.xyz - pi.xyz;
  float len = length3(e);
  precise float limit = params.stretch_limit * rest_length(i, direction);
  if (!(len > limit)) return;
  precise float excess = (len - limit) * (1.0 / len);
  precise vec3 corr = e * excess;
  precise float inv_wsum = 1.0 / wsum;
  precise vec3 ci = corr * (pi.w * inv_wsum);
  precise vec3 cj = corr * (pj.w * inv_wsum);
  precise vec3 xi = pi.xyz + ci;
  precise vec3 xj = pj.xyz - cj;
  // Both ends' x_prev stay: the correction goes into the displacements too.
  precise vec3 di = displacement_of(i).xyz + ci;
  precise vec3 dj = displacement_of(j).xyz - cj;
  pos[i].xyz = xi;
  pos[j].xyz = xj;
  disp[i] = vec4(di, 0.0);
  disp[j] = vec4(dj, 0.0);
}

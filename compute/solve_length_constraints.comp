// Reads (through the views) and writes positions and displacements in place. Dispatched once
// per colour over that colour's span (colour_span in host/core/spring_grid.hpp): one invocation
// per spring of the colour, and no two springs of a colour share a particle, so the writes never
// race (Provot 1995). The CPU twin is solve_length_constraint_colour.
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"
#include "constraint_colour.glsl"

layout(local_size_x = GRID_WORKGROUP_X, local_size_y = GRID_WORKGROUP_Y) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };

void main() {
  int i, j, direction;
  if (!colour_spring(ivec2(gl_GlobalInvocationID.xy), i, j, direction)) return;
  vec4 pi = position_of(i), pj = position_of(j);
  precise float wsum = pi.w + pj.w;
  if (wsum == 0.0) return;  // both ends pinned
  vec3 xi = pi.xyz, xj = pj.xyz;
  vec3 di = displacement_of(i).xyz, dj = displacement_of(j).xyz;
  precise float limit = params.stretch_limit * rest_length(i, direction);
  if (!limit_stretch(xi, xj, di, dj, pi.w, pj.w, wsum, limit)) return;
  pos[i].xyz = xi;
  pos[j].xyz = xj;
  disp[i] = vec4(di, 0.0);
  disp[j] = vec4(dj, 0.0);
}

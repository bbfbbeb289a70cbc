// Reads (through the views) and writes positions and displacements in place. The xpbd
// solver's constraint pass (docs/model.md): dispatched once per colour over that colour's span
// (colour_span in host/core/spring_grid.hpp), one invocation per spring; no two springs of a
// colour share a particle, so the writes never race. Each spring's XPBD distance constraint is
// solved once (its multiplier starts at zero every substep), then max_stretch is enforced as a
// hard limit in the same visit. The CPU twin is solve_distance_constraint_colour.
#include "layout.glsl"
#include "common.glsl"
#include "spring_grid.glsl"
#include "particle_views.glsl"
#include "collide_objects.glsl"

layout(local_size_x = GRID_WORKGROUP_X, local_size_y = GRID_WORKGROUP_Y) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };

uniform int u_colour;
// The span of every colour, set once for the grid: u_spans[2 c] along x, u_spans[2 c + 1] along y.
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
  float rest = rest_length(i, direction);
  float alpha = direction_type(direction) == 2 ? params.alpha_bending : params.alpha;
  precise vec3 xi = pi.xyz, xj = pj.xyz;
  precise vec3 di = displacement_of(i).xyz, dj = displacement_of(j).xyz;
  precise vec3 e = xj - xi;
  float len = length3(e);
  if (len > 0.0) {
    // dlambda = -C / (w_i + w_j + alpha~), C = len - rest; i and j move along e by their w.
    precise float scale = (len - rest) * (1.0 / len) * (1.0 / (wsum + alpha));
    precise vec3 corr = e * scale;
    precise vec3 ci = corr * pi.w;
    precise vec3 cj = corr * pj.w;
    xi = xi + ci;
    xj = xj - cj;
    di = di + ci;
    dj = dj - cj;
    e = xj - xi;
    len = length3(e);
  }
  precise float limit = params.stretch_limit * rest;
  if (len > limit) {
    precise float excess = (len - limit) * (1.0 / len);
    precise vec3 corr = e * excess;
    precise float inv_wsum = 1.0 / wsum;
    precise vec3 ci = corr * (pi.w * inv_wsum);
    precise vec3 cj = corr * (pj.w * inv_wsum);
    xi = xi + ci;
    xj = xj - cj;
    di = di + ci;
    dj = dj - cj;
  }
  // A correction must not push a mass into a collider or through a plane, where the collision
  // test of the next substep could no longer see it (docs/model.md).
  if (params.sphere_count + params.plane_count > 0u) {
    vec3 a = xi, b = xj, da = di, db = dj;
    if (pi.w != 0.0) collide_with_objects_friction(a, da, false);
    if (pj.w != 0.0) collide_with_objects_friction(b, db, false);
    xi = a;
    xj = b;
    di = da;
    dj = db;
  }
  pos[i].xyz = xi;
  pos[j].xyz = xj;
  disp[i] = vec4(di, 0.0);
  disp[j] = vec4(dj, 0.0);
}

// What the two constraint passes (solve_length_constraints, solve_distance_constraints) share:
// the spring of this invocation within one colour's span, and Provot's stretch limit. The CPU
// twins are for_each_spring_of_colour and limit_stretch in host/core/reference_constraints.cpp.
#ifndef CLOTHSIM_CONSTRAINT_COLOUR_GLSL
#define CLOTHSIM_CONSTRAINT_COLOUR_GLSL

#include "spring_grid.glsl"

uniform int u_colour;
// The span of every colour (colour_span in host/core/spring_grid.hpp), set once for the grid:
// u_spans[2 c] along x, u_spans[2 c + 1] along y, each an AxisSpan (first, period, shift, count).
uniform ivec4 u_spans[2 * NUM_COLOURS];

int span_coord(ivec4 s, int k) { return s.x + s.y * (k >> s.z) + (k & ((1 << s.z) - 1)); }

// The spring of invocation k of colour u_colour: it runs from particle i to j along `direction`.
// False for an invocation past the span's end.
bool colour_spring(ivec2 k, out int i, out int j, out int direction) {
  ivec4 span_x = u_spans[2 * u_colour], span_y = u_spans[2 * u_colour + 1];
  direction = u_colour >> 1;
  i = 0;
  j = 0;
  if (k.x >= span_x.w || k.y >= span_y.w) return false;
  ivec2 c = ivec2(span_coord(span_x, k.x), span_coord(span_y, k.y));
  i = grid_index(c);
  j = grid_index(c + direction_offset(direction));
  return true;
}

// Provot's projection: a spring from xi to xj longer than `limit` is shortened to it, both
// ends moving by their share of the inverse mass (wi, wj, wsum = wi + wj > 0), the
// displacements with them (the ends' x_prev stay). False, and nothing moves, if it is not longer.
bool limit_stretch(inout vec3 xi, inout vec3 xj, inout vec3 di, inout vec3 dj, float wi, float wj, float wsum,
                   float limit) {
  vec3 e = xj - xi;
  float len = length3(e);
  if (!(len > limit)) return false;
  precise float excess = (len - limit) * (1.0 / len);
  precise vec3 corr = e * excess;
  precise float inv_wsum = 1.0 / wsum;
  precise vec3 ci = corr * (wi * inv_wsum);
  precise vec3 cj = corr * (wj * inv_wsum);
  precise vec3 nxi = xi + ci, nxj = xj - cj, ndi = di + ci, ndj = dj - cj;
  xi = nxi;
  xj = nxj;
  di = ndi;
  dj = ndj;
  return true;
}

#endif

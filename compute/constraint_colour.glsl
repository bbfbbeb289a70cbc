// What the two constraint passes (solve_length_constraints, solve_distance_constraints) share:
// the spring of this invocation within one colour, and Provot's stretch limit. The CPU
// twins are for_each_spring_of_colour and limit_stretch in host/core/reference/reference_constraints.cpp.
#ifndef CLOTHSIM_CONSTRAINT_COLOUR_GLSL
#define CLOTHSIM_CONSTRAINT_COLOUR_GLSL

#include "particle_views.glsl"

// The colour being solved: springs [u_first, u_first + u_count) of the sorted list
// (ClothModel::colour_start), set by the host before each dispatch.
uniform uint u_first;
uniform uint u_count;

// The spring of invocation k of this colour: from particle i to j, its rest length, type and
// material. False for an invocation past the colour's end.
bool colour_spring(uint k, out int i, out int j, out float rest, out uint type, out int material_index) {
  i = 0;
  j = 0;
  rest = 0.0;
  type = 0u;
  material_index = 0;
  if (k >= u_count) return false;
  uvec4 s = texelFetch(springs_view, int(u_first + k));
  i = int(s.x);
  j = int(s.y);
  rest = uintBitsToFloat(s.z);
  type = s.w & 3u;
  material_index = int(s.w >> 2);
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

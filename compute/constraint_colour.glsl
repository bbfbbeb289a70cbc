// What the two constraint passes (solve_length_constraints, solve_distance_constraints) share:
// the spring of this invocation within one colour, and Provot's stretch limit
// (compute/shared/springs.glsl).
#ifndef CLOTHSIM_CONSTRAINT_COLOUR_GLSL
#define CLOTHSIM_CONSTRAINT_COLOUR_GLSL

#include "particle_views.glsl"
#include "shared/springs.glsl"

// The colour being solved: springs [u_first, u_first + u_count) of the sorted list
// (ClothModel::colour_start), set by the host before each dispatch.
uniform uint u_first;
uniform uint u_count;

// The spring of invocation k of this colour: from particle i to j, its rest length now (a
// seam's shrinks: seam_rest), type and material. False for an invocation past the colour's end.
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
  if (type == SEAM_SPRING) rest = seam_rest(rest, control.seam_shrink);
  return true;
}

#endif

// The force on one particle (DESIGN.md §1.1): gravity plus its up to twelve springs, summed
// in kGatherOrder (per direction, the spring stored here, then the one stored at the
// neighbour behind), exactly as accumulate_forces in host/core/reference.cpp. Unrolled: the
// direction of every call is a constant, so offsets and spring constants fold away.
#ifndef CLOTHSIM_FORCES_GLSL
#define CLOTHSIM_FORCES_GLSL

#include "particle_views.glsl"
#include "spring_grid.glsl"

vec3 add_spring(vec3 f, vec3 xi, int j, float rest, float k_spring) {
  vec3 e = position_of(j).xyz - xi;
  float len = length3(e);
  if (!(len > 0.0)) return f;
  precise float inv = 1.0 / len;
  precise float magnitude = k_spring * (len - rest) * inv;
  precise vec3 sum = f + e * magnitude;
  return sum;
}

vec3 add_direction(vec3 f, vec3 xi, ivec2 c, int i, int direction, float rest_here) {
  if (!spring_enabled(direction)) return f;
  float k_spring = direction_type(direction) == 2 ? params.ks_bending : params.ks;
  ivec2 off = direction_offset(direction);
  int step = off.y * int(params.width) + off.x;
  if (in_grid(c + off)) f = add_spring(f, xi, i + step, rest_here, k_spring);
  if (in_grid(c - off)) f = add_spring(f, xi, i - step, rest_length(i - step, direction), k_spring);
  return f;
}

vec3 spring_force(ivec2 c, int i, vec3 xi) {
  precise vec3 f = params.gravity * params.mass;
  vec4 near = texelFetch(rest_view, REST_TEXELS * i), far = texelFetch(rest_view, REST_TEXELS * i + 1);
  f = add_direction(f, xi, c, i, DIR_RIGHT, near.x);
  f = add_direction(f, xi, c, i, DIR_DOWN, near.y);
  f = add_direction(f, xi, c, i, DIR_DIAG_DOWN_RIGHT, near.z);
  f = add_direction(f, xi, c, i, DIR_DIAG_DOWN_LEFT, near.w);
  f = add_direction(f, xi, c, i, DIR_RIGHT2, far.x);
  f = add_direction(f, xi, c, i, DIR_DOWN2, far.y);
  return f;
}

#endif

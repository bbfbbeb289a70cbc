// One particle against every sphere in file order, then every plane (DESIGN.md §1.4), as
// collide_objects in host/core/reference.cpp. x is its position, d its displacement of this
// substep (x_prev = x - d); both change. Shared by collide_objects.comp and the passes it is
// fused into (advance, resolve_self_contacts).
#ifndef CLOTHSIM_COLLIDE_OBJECTS_GLSL
#define CLOTHSIM_COLLIDE_OBJECTS_GLSL

#include "particle_views.glsl"

// The friction blend x' = x_prev + keep (t - x_prev), as d' = keep ((t - x) + d),
// x' = x + (d' - d): only small differences are rounded.
void blend_to(vec3 t_minus_x, float keep, inout vec3 x, inout vec3 d) {
  precise vec3 next_d = (t_minus_x + d) * keep;
  precise vec3 next_x = x + (next_d - d);
  x = next_x;
  d = next_d;
}

void collide_with_objects(inout vec3 x, inout vec3 d) {
  for (int s = 0; s < int(params.sphere_count); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    float keep = texelFetch(spheres_view, SPHERE_TEXELS * s + 1).x;
    float r = origin_radius.w;
    vec3 e = x - origin_radius.xyz;
    float dist = length3(e);
    if (dist > r) continue;
    precise vec3 t_minus_x;
    if (dist > 0.0) {
      precise float scale = (r - dist) * (1.0 / dist);
      t_minus_x = e * scale;
    } else {
      t_minus_x = vec3(0.0, r, 0.0);  // at the centre there is no outward direction: push up
    }
    blend_to(t_minus_x, keep, x, d);
  }
  for (int k = 0; k < int(params.plane_count); ++k) {
    vec3 q = texelFetch(planes_view, PLANE_TEXELS * k).xyz;
    vec4 normal_keep = texelFetch(planes_view, PLANE_TEXELS * k + 1);
    vec3 n = normal_keep.xyz;
    float dist = dot3(x - q, n);
    precise float dist_prev = dist - dot3(d, n);
    precise float crossing = dist * dist_prev;
    if (crossing > 0.0) continue;
    float side = dist_prev > 0.0 ? 1.0 : (dist_prev < 0.0 ? -1.0 : 0.0);
    precise float along = 1e-4 * side - dist;
    precise vec3 t_minus_x = n * along;
    blend_to(t_minus_x, normal_keep.w, x, d);
  }
}

#endif

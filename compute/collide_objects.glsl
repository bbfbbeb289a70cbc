// One particle against every sphere in file order, then every plane (DESIGN.md §1.4), as
// collide_objects in host/core/reference.cpp. x is its position, xp its previous position.
// Shared by collide_objects.comp and the passes it is fused into (advance, collide_self).
#ifndef CLOTHSIM_COLLIDE_OBJECTS_GLSL
#define CLOTHSIM_COLLIDE_OBJECTS_GLSL

#include "particle_views.glsl"

vec3 collide_with_objects(vec3 x_in, vec3 xp) {
  precise vec3 x = x_in;
  for (int s = 0; s < int(params.sphere_count); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    float keep = texelFetch(spheres_view, SPHERE_TEXELS * s + 1).x;
    vec3 o = origin_radius.xyz;
    float r = origin_radius.w;
    vec3 e = x - o;
    float d = length3(e);
    if (d > r) continue;
    precise vec3 t;
    if (d > 0.0) {
      precise float scale = r * (1.0 / d);
      t = o + e * scale;
    } else {
      t = o + vec3(0.0, r, 0.0);  // at the centre there is no outward direction: push up
    }
    x = xp + (t - xp) * keep;
  }
  for (int k = 0; k < int(params.plane_count); ++k) {
    vec3 q = texelFetch(planes_view, PLANE_TEXELS * k).xyz;
    vec4 normal_keep = texelFetch(planes_view, PLANE_TEXELS * k + 1);
    vec3 n = normal_keep.xyz;
    float d = dot3(x - q, n);
    float dp = dot3(xp - q, n);
    precise float crossing = d * dp;
    if (crossing > 0.0) continue;
    float side = dp > 0.0 ? 1.0 : (dp < 0.0 ? -1.0 : 0.0);
    precise float lift = 1e-4 * side;
    precise vec3 t = x - n * d + n * lift;
    x = xp + (t - xp) * normal_keep.w;
  }
  return x;
}

#endif

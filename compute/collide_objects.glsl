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

// The blend relative to a collider that moved by m this substep (docs/model.md): in its frame
// x_prev is x_prev + m, so d' = keep ((t - x) + d - m) + m.
void blend_to_moving(vec3 t_minus_x, float keep, vec3 m, inout vec3 x, inout vec3 d) {
  precise vec3 next_d = ((t_minus_x + d) - m) * keep + m;
  precise vec3 next_x = x + (next_d - d);
  x = next_x;
  d = next_d;
}

// A moving sphere's push-out: along e = x - o, unless the motion relative to the sphere
// carried the mass past the centre this substep (e . e_prev < 0, e_prev = e - d + m): then back
// out on the side it came from, along e_prev, so that a fast sphere cannot pass through.
vec3 moving_sphere_push(vec3 e, float dist, float r, vec3 d, vec3 m) {
  precise vec3 e_prev = (e - d) + m;
  float prev_dist = length3(e_prev);
  if (dot3(e, e_prev) < 0.0 && prev_dist > 0.0) {
    precise float inv_prev = 1.0 / prev_dist;
    precise vec3 back = e_prev * (r * inv_prev) - e;
    return back;
  }
  if (!(dist > 0.0)) return vec3(0.0, r, 0.0);
  precise float scale = (r - dist) * (1.0 / dist);
  precise vec3 out_along_e = e * scale;
  return out_along_e;
}

// With `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out that xpbd's constraint pass applies after each correction (docs/model.md); applying
// it twice changes nothing.
void collide_with_objects_friction(inout vec3 x, inout vec3 d, bool friction) {
  for (int s = 0; s < int(params.sphere_count); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    float keep = friction ? texelFetch(spheres_view, SPHERE_TEXELS * s + 1).x : 1.0;
    vec3 m = texelFetch(spheres_view, SPHERE_TEXELS * s + 2).xyz;
    float r = origin_radius.w;
    vec3 e = x - origin_radius.xyz;
    float dist = length3(e);
    if (dist > r) continue;
    if (any(notEqual(m, vec3(0.0)))) {
      blend_to_moving(moving_sphere_push(e, dist, r, d, m), keep, m, x, d);
      continue;
    }
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
    vec3 m = texelFetch(planes_view, PLANE_TEXELS * k + 2).xyz;
    vec3 n = normal_keep.xyz;
    if (!friction) normal_keep.w = 1.0;
    if (any(notEqual(m, vec3(0.0)))) {
      // The side test in the plane's frame, x_prev - p_prev = (x - p) - (d - m): it sees a
      // plane that swept over a mass at any speed.
      float dist = dot3(x - q, n);
      precise vec3 rel_d = d - m;
      precise float dist_prev = dist - dot3(rel_d, n);
      precise float crossing = dist * dist_prev;
      if (crossing > 0.0) continue;
      float side = dist_prev > 0.0 ? 1.0 : (dist_prev < 0.0 ? -1.0 : 0.0);
      precise float along = 1e-4 * side - dist;
      precise vec3 t_minus_x = n * along;
      blend_to_moving(t_minus_x, normal_keep.w, m, x, d);
      continue;
    }
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

void collide_with_objects(inout vec3 x, inout vec3 d) { collide_with_objects_friction(x, d, true); }

#endif

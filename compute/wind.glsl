// The aerodynamic force of the air on the cloth (docs/model.md, "Wind"), per particle as a
// gather over the up to six triangles around it; the formulas are compute/shared/wind.glsl's.
// Reads positions and displacements of the particle and its neighbours through the views, so it
// runs in its own pass (compute_wind_forces.comp) before the one that writes them (advance, or
// XPBD's predict), which adds wind_force_of(i) to its force.
#ifndef CLOTHSIM_WIND_GLSL
#define CLOTHSIM_WIND_GLSL

#include "particle_views.glsl"
#include "shared/wind.glsl"

// One corner's share of triangle (a, b, c)'s force, from its corners' positions and
// displacements.
vec3 triangle_wind_share(int a, int b, int c) {
  vec3 pa = position_of(a).xyz, pb = position_of(b).xyz, pc = position_of(c).xyz;
  vec3 air = air_velocity(params.gust_enabled != 0u, params.wind_velocity, params.gust_velocity, control.gust_phase,
                          params.wind_direction, params.gust_inv_length3, pa, pb, pc);
  precise vec3 moved = (displacement_of(a).xyz + displacement_of(b).xyz) + displacement_of(c).xyz;
  return triangle_wind_share(pa, pb, pc, moved, air, params.wind_inv_3dt, params.wind_drag, params.wind_lift);
}

// The wind force on particle i: its shares of the triangles around it, in compute_normals'
// order (the model's corner lists, ascending).
vec3 gather_wind_force(int i) {
  precise vec3 f = vec3(0.0);
  for (uint k = corners_first(i); k < corners_first(i + 1); ++k) {
    ivec3 t = corner_triangle(k);
    f = f + triangle_wind_share(t.x, t.y, t.z);
  }
  return f;
}

#endif

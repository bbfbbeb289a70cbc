// The aerodynamic force of the air on the cloth (docs/model.md, "Wind"), per particle as a
// gather over the up to six triangles around it, exactly as compute_wind_forces and
// triangle_wind_share in host/core/reference/reference.cpp. Reads positions and displacements of the
// particle and its neighbours through the views, so it runs in its own pass
// (compute_wind_forces.comp) before the one that writes them (advance, or XPBD's predict),
// which adds wind_force_of(i) to its force.
#ifndef CLOTHSIM_WIND_GLSL
#define CLOTHSIM_WIND_GLSL

#include "particle_views.glsl"

// The parabolic stand-in for sin(2 pi phase): + - * and floor only, which both backends
// round alike (GLSL's sin does not match std::sin).
float gust_wave(float phase) {
  precise float w = phase - floor(phase);
  precise float h = w < 0.5 ? w : w - 0.5;
  precise float bump = 16.0 * h * (0.5 - h);
  return w < 0.5 ? bump : -bump;
}

// The share of one corner in the force on triangle (a, b, c): drag -1/2 rho C_d A |v| (v.n) n,
// lift -1/2 rho C_l A (v.n) (|v| n - (v.n)/|v| v), v the triangle's velocity relative to the air
// (params.wind_drag and wind_lift fold 1/2 rho C, the area as half the cross product, and 1/3).
vec3 triangle_wind_share(int a, int b, int c) {
  vec3 pa = position_of(a).xyz, pb = position_of(b).xyz, pc = position_of(c).xyz;
  precise vec3 u = pb - pa, v = pc - pa;
  precise vec3 twice_area_n = vec3(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
  float len = length3(twice_area_n);
  if (!(len > 0.0)) return vec3(0.0);
  precise float inv_len = 1.0 / len;
  precise vec3 n = twice_area_n * inv_len;
  precise vec3 air = params.wind_velocity;
  if (params.gust_enabled != 0u) {
    precise vec3 corners = (pa + pb) + pc;
    precise float phase = params.gust_phase - dot3(corners, params.wind_direction) * params.gust_inv_length3;
    precise vec3 gust = params.wind_velocity + params.gust_velocity * gust_wave(phase);
    air = gust;
  }
  precise vec3 moved = (displacement_of(a).xyz + displacement_of(b).xyz) + displacement_of(c).xyz;
  precise vec3 rel = moved * params.wind_inv_3dt - air;
  float speed = length3(rel);
  if (!(speed > 0.0)) return vec3(0.0);
  float normal_speed = dot3(rel, n);
  precise vec3 drag = n * (params.wind_drag * len * speed * normal_speed);
  precise float inv_speed = 1.0 / speed;
  precise vec3 across = n * speed - rel * (normal_speed * inv_speed);
  precise vec3 f = drag + across * (params.wind_lift * len * normal_speed);
  return f;
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

// The aerodynamic force of the air on a triangle (docs/model.md, "Wind") and the gusts' wave.
// Included by compute/wind.glsl and host/core/reference/reference_forces.cpp; the gather over the
// triangles around a particle, and the reads of their corners, stay with each backend.
#ifndef CLOTHSIM_SHARED_WIND_GLSL
#define CLOTHSIM_SHARED_WIND_GLSL

#include "vector.glsl"

SHARED_BEGIN

// The parabolic stand-in for sin(2 pi phase) of the gusts: + - * and floor only, which both
// backends round alike (a shader's sin does not match std::sin); within 0.056 of the sine.
SHARED_FN REAL gust_wave(REAL phase) {
  PRECISE REAL w = phase - floor(phase);
  PRECISE REAL h = w < REAL(0.5) ? w : w - REAL(0.5);
  PRECISE REAL bump = REAL(16) * h * (REAL(0.5) - h);
  return w < REAL(0.5) ? bump : -bump;
}

// The air's velocity at triangle (pa, pb, pc): the wind's, plus with `gusts` the gust velocity
// times the wave at the centroid's phase (gust_inv_length3 = 1 / (3 length): the phase of the
// sum of the corners along the wind's direction).
SHARED_FN VEC3 air_velocity(bool gusts, VEC3 velocity, VEC3 gust_velocity, REAL gust_phase, VEC3 direction,
                            REAL gust_inv_length3, VEC3 pa, VEC3 pb, VEC3 pc) {
  PRECISE VEC3 air = velocity;
  if (gusts) {
    PRECISE VEC3 corners = (pa + pb) + pc;
    PRECISE REAL phase = gust_phase - dot3(corners, direction) * gust_inv_length3;
    PRECISE VEC3 gust = velocity + gust_velocity * gust_wave(phase);
    air = gust;
  }
  return air;
}

// The share of one corner in the force on triangle (pa, pb, pc), its corners having moved
// `moved` together this substep (times inv_3dt: the triangle's velocity) in air of velocity
// `air`: drag -1/2 rho C_d A |v| (v.n) n, lift -1/2 rho C_l A (v.n) (|v| n - (v.n)/|v| v), v the
// velocity relative to the air (drag and lift fold 1/2 rho C, the area as half the cross
// product, and 1/3). |v| n - (v.n)/|v| v is |v| times the part of n across v.
SHARED_FN VEC3 triangle_wind_share(VEC3 pa, VEC3 pb, VEC3 pc, VEC3 moved, VEC3 air, REAL inv_3dt, REAL drag,
                                   REAL lift) {
  PRECISE VEC3 u = pb - pa;
  PRECISE VEC3 v = pc - pa;
  VEC3 twice_area_n = cross3(u, v);
  REAL len = length3(twice_area_n);
  if (!(len > REAL(0))) return VEC3(REAL(0));  // a degenerate triangle catches no air
  PRECISE REAL inv_len = REAL(1) / len;
  PRECISE VEC3 n = twice_area_n * inv_len;
  PRECISE VEC3 rel = moved * inv_3dt - air;
  REAL speed = length3(rel);
  if (!(speed > REAL(0))) return VEC3(REAL(0));
  REAL normal_speed = dot3(rel, n);
  PRECISE VEC3 drag_part = n * (drag * len * speed * normal_speed);
  PRECISE REAL inv_speed = REAL(1) / speed;
  PRECISE VEC3 across = n * speed - rel * (normal_speed * inv_speed);
  PRECISE VEC3 f = drag_part + across * (lift * len * normal_speed);
  return f;
}

SHARED_END

#endif

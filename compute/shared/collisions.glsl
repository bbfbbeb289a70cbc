// The analytic colliders' formulas (docs/design.md §1.4, docs/model.md): a sphere's push-out and
// swept test, a plane's crossing test, and the pushes back to their surfaces. Included by
// compute/collide_objects.glsl and host/core/reference/reference_detail.hpp; the loops over the
// colliders and the reads of their parameters stay with each backend.
#ifndef CLOTHSIM_SHARED_COLLISIONS_GLSL
#define CLOTHSIM_SHARED_COLLISIONS_GLSL

#include "friction.glsl"

SHARED_BEGIN

// t - x = e (r / |e| - 1) for a mass inside a sphere (e = x - o, dist = |e|, e_prev = e at the
// substep's start in the sphere's frame): the push out to the surface (a mass exactly at the
// centre has no outward direction: it goes up), unless it passed the centre this substep
// (e . e_prev < 0, a mass or a sphere faster than the radius per substep): then back out on the
// side it came from, along e_prev, so that nothing tunnels at any speed.
SHARED_FN VEC3 sphere_push(VEC3 e, REAL dist, REAL r, VEC3 e_prev) {
  REAL prev_dist = length3(e_prev);
  if (dot3(e, e_prev) < REAL(0) && prev_dist > REAL(0)) {
    PRECISE REAL inv_prev = REAL(1) / prev_dist;
    PRECISE VEC3 back = e_prev * (r * inv_prev) - e;
    return back;
  }
  if (!(dist > REAL(0))) return VEC3(REAL(0), r, REAL(0));
  PRECISE REAL scale = (r - dist) * (REAL(1) / dist);
  PRECISE VEC3 out_along_e = e * scale;
  return out_along_e;
}

// A moving sphere (it moved by m this substep): e_prev = x_prev - o_prev = e - d + m.
SHARED_FN VEC3 moving_sphere_push(VEC3 e, REAL dist, REAL r, VEC3 d, VEC3 m) {
  PRECISE VEC3 e_prev = (e - d) + m;
  return sphere_push(e, dist, r, e_prev);
}

// A static sphere: e_prev = e - d.
SHARED_FN VEC3 static_sphere_push(VEC3 e, REAL dist, REAL r, VEC3 d) {
  PRECISE VEC3 e_prev = e - d;
  return sphere_push(e, dist, r, e_prev);
}

// The first test of passed_through_sphere: a path of length |rel| that ends `dist - r` outside
// the sphere cannot have entered it (the common case costs one comparison). Also may_collide's,
// on the same values: the same decision.
SHARED_FN bool path_stays_outside(REAL dist, REAL r, VEC3 rel) {
  PRECISE REAL gap = dist - r;
  REAL a = dot3(rel, rel);
  PRECISE REAL gap2 = gap * gap;
  return !(a > gap2);
}

// A mass outside a sphere at the end of the substep, e = x - o (|e| = dist > r), that moved by
// rel = d - m relative to it: true if its path e - rel .. e went into the sphere deeper than
// 0.1 mm (a fast mass, or a fast sphere, passing through within the substep), with t - x the
// push back to where the path entered the surface.
SHARED_FN bool passed_through_sphere(VEC3 e, REAL dist, REAL r, VEC3 rel, OUT(VEC3) t_minus_x) {
  t_minus_x = VEC3(REAL(0));
  if (path_stays_outside(dist, r, rel)) return false;
  REAL a = dot3(rel, rel);
  PRECISE VEC3 e_prev = e - rel;
  REAL b = dot3(e_prev, rel);  // the path is e_prev + s rel, s in [0, 1]
  if (!(b < REAL(0))) return false;  // moving away from the centre: leaving, not passing through
  PRECISE REAL inv_a = REAL(1) / a;
  PRECISE REAL s_closest = min(REAL(1), -b * inv_a);
  PRECISE VEC3 closest = e_prev + rel * s_closest;
  PRECISE REAL depth = r - length3(closest);
  if (!(depth > REAL(1e-4))) return false;
  PRECISE REAL c = dot3(e_prev, e_prev) - r * r;
  if (c > REAL(0)) {
    PRECISE REAL disc = b * b - a * c;  // > 0: the path meets the sphere
    PRECISE REAL s_in = (-b - sqrt(disc)) * inv_a;
    PRECISE VEC3 entry = (e_prev + rel * s_in) - e;
    t_minus_x = entry;
  } else {
    // It started on the surface (where the last contact put it) or inside: back out on its own side.
    REAL prev_dist = length3(e_prev);
    PRECISE REAL inv_prev = REAL(1) / prev_dist;
    PRECISE VEC3 back = e_prev * (r * inv_prev) - e;
    PRECISE VEC3 up = VEC3(REAL(0), r, REAL(0)) - e;
    t_minus_x = prev_dist > REAL(0) ? back : up;
  }
  return true;
}

// The friction blend moves a mass from x_prev towards the surface point t, and a chord between
// two points of a sphere runs inside it: a fast mass sliding over a sphere can end the blend
// deep inside. Deeper than 0.1 mm it is put back on the surface along e, without friction.
SHARED_FN void keep_out_of_sphere(VEC3 o, REAL r, INOUT(VEC3) x, INOUT(VEC3) d) {
  VEC3 e = x - o;
  REAL dist = length3(e);
  PRECISE REAL depth = r - dist;
  if (!(depth > REAL(1e-4)) || !(dist > REAL(0))) return;
  PRECISE REAL scale = depth * (REAL(1) / dist);
  PRECISE VEC3 out_along_e = e * scale;
  PRECISE VEC3 nx = x + out_along_e;
  PRECISE VEC3 nd = d + out_along_e;
  x = nx;
  d = nd;
}

// A mass deeper than 0.1 mm behind a plane's front goes to its surface offset on the front,
// along the normal n, without friction: after Provot's pull, and after the CS184 blend of a mass
// found behind (the blend starts from x_prev, behind too, so it can end still behind).
SHARED_FN void keep_in_front_of_plane(VEC3 p, VEC3 n, REAL front, INOUT(VEC3) x, INOUT(VEC3) d) {
  REAL dist = dot3(x - p, n);
  PRECISE REAL behind = dist * front;
  if (!(behind < REAL(-1e-4))) return;
  PRECISE REAL along = REAL(1e-4) * front - dist;
  PRECISE VEC3 out_along_n = n * along;
  PRECISE VEC3 nx = x + out_along_n;
  PRECISE VEC3 nd = d + out_along_n;
  x = nx;
  d = nd;
}

// The outward normal of a sphere at the point x + t_minus_x (up at the centre).
SHARED_FN VEC3 sphere_normal(VEC3 o, VEC3 x, VEC3 t_minus_x) {
  PRECISE VEC3 e = (x + t_minus_x) - o;
  return unit_or_up(e);
}

// One sphere contact's response: xpbd's Coulomb friction when `coulomb`, else the CS184 blend
// keeping `keep`, in the sphere's frame when it moves by m.
SHARED_FN void respond_to_sphere(bool coulomb, VEC3 o, REAL keep, REAL mu, VEC3 m, VEC3 t_minus_x, INOUT(VEC3) x,
                                 INOUT(VEC3) d) {
  if (coulomb) coulomb_respond(t_minus_x, sphere_normal(o, x, t_minus_x), mu, m, x, d);
  else if (nonzero3(m)) blend_to_moving(t_minus_x, keep, m, x, d);
  else blend_to(t_minus_x, keep, x, d);
}

// The plane's crossing test in its frame (x_prev - p_prev = (x - p) - (d - m), so a sweep is
// seen at any speed): the signed distances of the substep's end and start, and whether they
// differ in sign (or one is 0).
SHARED_FN bool plane_sides(VEC3 x, VEC3 d, VEC3 p, VEC3 n, VEC3 m, OUT(REAL) dist, OUT(REAL) dist_prev) {
  dist = dot3(x - p, n);
  PRECISE VEC3 rel_d = d - m;
  PRECISE REAL prev = dist - dot3(rel_d, n);
  dist_prev = prev;
  PRECISE REAL crossing = dist * dist_prev;
  return !(crossing > REAL(0));
}

// A mass that did not cross: untouched while it ends in front by more than the contact offset
// (1e-4 with Coulomb friction: resting contact) or, without, anywhere in front.
SHARED_FN bool stays_in_front(REAL dist, REAL front, bool coulomb) {
  PRECISE REAL ahead = dist * front;
  return !(ahead < (coulomb ? REAL(1e-4) : REAL(0)));
}

// A plane contact's response: a mass that crossed goes back to the side it came from (side: the
// sign of dist_prev), one found behind the front to the front (side = front), to the surface
// offset on that side, t = x - dist n + 1e-4 side n; the outward normal is n times the side.
SHARED_FN void respond_to_plane(bool coulomb, VEC3 n, REAL front, REAL keep, REAL mu, VEC3 m, REAL dist, REAL side,
                                INOUT(VEC3) x, INOUT(VEC3) d) {
  PRECISE REAL along = REAL(1e-4) * side - dist;
  PRECISE VEC3 t_minus_x = n * along;
  PRECISE VEC3 outward = n * (side != REAL(0) ? side : front);
  respond_to_contact(coulomb, t_minus_x, outward, keep, mu, m, x, d);
}

// The side a plane's contact pushes to (respond_to_plane).
SHARED_FN REAL plane_side(bool crossed, REAL dist_prev, REAL front) {
  if (!crossed) return front;
  return dist_prev > REAL(0) ? REAL(1) : (dist_prev < REAL(0) ? REAL(-1) : REAL(0));
}

// Whether a mass at x is within `reach` of a sphere's surface or inside it (the multigrid
// solver's touches_colliders).
SHARED_FN bool near_sphere(VEC3 x, VEC3 o, REAL r, REAL reach) {
  PRECISE REAL within = r + reach;
  return length3(x - o) < within;
}

// Whether a mass at x is behind a plane's front or within `reach` in front of it.
SHARED_FN bool near_plane(VEC3 x, VEC3 p, VEC3 n, REAL front, REAL reach) {
  PRECISE REAL ahead = dot3(x - p, n) * front;
  return ahead < reach;
}

SHARED_END

#endif

// The contact responses every collider shares: the CS184 friction blend (static and moving
// colliders) and xpbd's Coulomb friction. Included by compute/shared/collisions.glsl, and so by
// compute/collide_objects.glsl and host/core/reference/reference_detail.hpp.
#ifndef CLOTHSIM_SHARED_FRICTION_GLSL
#define CLOTHSIM_SHARED_FRICTION_GLSL

#include "vector.glsl"

SHARED_BEGIN

// The friction blend x' = x_prev + keep (t - x_prev) with x_prev = x - d, written as
// d' = keep ((t - x) + d), x' = x + (d' - d): every rounded difference is small.
SHARED_FN void blend_to(VEC3 t_minus_x, REAL keep, INOUT(VEC3) x, INOUT(VEC3) d) {
  PRECISE VEC3 next_d = (t_minus_x + d) * keep;
  PRECISE VEC3 next_x = x + (next_d - d);
  x = next_x;
  d = next_d;
}

// The blend relative to a collider that moved by m this substep: in its frame the previous
// position is x_prev + m, so x' = (x_prev + m) + keep (t - (x_prev + m)), i.e.
// d' = keep ((t - x) + d - m) + m: friction damps the motion relative to the collider's.
SHARED_FN void blend_to_moving(VEC3 t_minus_x, REAL keep, VEC3 m, INOUT(VEC3) x, INOUT(VEC3) d) {
  PRECISE VEC3 next_d = ((t_minus_x + d) - m) * keep + m;
  PRECISE VEC3 next_x = x + (next_d - d);
  x = next_x;
  d = next_d;
}

// xpbd's contact response (docs/model.md, "Coulomb friction"): the push t - x out along the
// contact normal n (unit, outwards), then Coulomb friction on the substep's displacement
// relative to the collider (d - m after the push): its tangential part is cancelled if it is at
// most mu times the push's depth along n (static friction), else shortened by that much
// (sliding). The depth is what the mass was pressed in over the substep (g cos(theta) dt^2 for a
// mass resting on a slope), so the friction is mu times the normal force at any substep length.
// The whole change, push and friction, is added to x once.
SHARED_FN void coulomb_respond(VEC3 t_minus_x, VEC3 n, REAL mu, VEC3 m, INOUT(VEC3) x, INOUT(VEC3) d) {
  PRECISE VEC3 pushed = d + t_minus_x;
  REAL depth = dot3(t_minus_x, n);
  VEC3 cancel = VEC3(REAL(0));
  if (depth > REAL(0) && mu > REAL(0)) {
    PRECISE VEC3 rel = pushed - m;
    PRECISE VEC3 tangential = rel - n * dot3(rel, n);
    REAL slide = length3(tangential);
    PRECISE REAL limit = mu * depth;
    PRECISE REAL inv_slide = REAL(1) / slide;
    PRECISE VEC3 part = tangential * (limit * inv_slide);
    if (slide > REAL(0)) cancel = slide <= limit ? tangential : part;
  }
  PRECISE VEC3 next_x = x + (t_minus_x - cancel);
  PRECISE VEC3 next_d = pushed - cancel;
  x = next_x;
  d = next_d;
}

// Whether a contact takes friction: always where `friction`, but in fabric's sweep
// (`still_only`) only against a collider that did not move this substep (m = 0). There the
// push-out's depth is mostly the local solve pulling a mass the collider pushed back towards its
// neighbours, which have not followed yet, not a normal force: friction on it held the cloth to a
// moving sphere far beyond Coulomb (sphere_sweep's largest stretch 6.9, against 1.36 when the
// model is integrated at 400 substeps; docs/solvers.md, "A fast collider").
SHARED_FN bool takes_friction(bool friction, bool still_only, VEC3 m) {
  return friction && !(still_only && nonzero3(m));
}

// A contact's response along the outward normal n: xpbd's Coulomb friction when `coulomb`,
// else the CS184 blend keeping `keep` (1: no friction), in the collider's frame when it moves
// by m.
SHARED_FN void respond_to_contact(bool coulomb, VEC3 t_minus_x, VEC3 n, REAL keep, REAL mu, VEC3 m, INOUT(VEC3) x,
                                  INOUT(VEC3) d) {
  if (coulomb) coulomb_respond(t_minus_x, n, mu, m, x, d);
  else if (nonzero3(m)) blend_to_moving(t_minus_x, keep, m, x, d);
  else blend_to(t_minus_x, keep, x, d);
}

SHARED_END

#endif

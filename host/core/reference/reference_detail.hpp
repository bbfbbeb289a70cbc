// Shared by the reference's pass files, not part of its interface.
#pragma once

#include "reference/reference.hpp"
#include "colliders/sdf.hpp"

namespace clothsim {

// One particle against every sphere, then every plane (reference_collisions.cpp). With
// `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out of xpbd's constraint pass.
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction);
// A mass deeper than 0.1 mm inside a sphere, or behind a plane's front, goes back to the
// surface (a plane's: its surface offset on the front), without friction; otherwise nothing.
template <class R> void keep_out_of_colliders(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d);

// The contact responses every collider shares (reference_collisions.cpp, and the mesh
// colliders of reference_mesh_collisions.cpp).
// The friction blend x' = x_prev + keep (t - x_prev) with x_prev = x - d, written as
// d' = keep ((t - x) + d), x' = x + (d' - d): every rounded difference is small.
template <class R> void blend_to(const Vec3<R>& t_minus_x, R keep, Vec3<R>& x, Vec3<R>& d) {
  const Vec3<R> next_d = (t_minus_x + d) * keep;
  x = x + (next_d - d);
  d = next_d;
}

// The blend relative to a collider that moved by m this substep: in its frame the previous
// position is x_prev + m, so x' = (x_prev + m) + keep (t - (x_prev + m)), i.e.
// d' = keep ((t - x) + d - m) + m: friction damps the motion relative to the collider's.
template <class R> void blend_to_moving(const Vec3<R>& t_minus_x, R keep, const Vec3<R>& m, Vec3<R>& x, Vec3<R>& d) {
  const Vec3<R> next_d = ((t_minus_x + d) - m) * keep + m;
  x = x + (next_d - d);
  d = next_d;
}

// xpbd's contact response (docs/model.md, "Coulomb friction"): the push t - x out along the
// contact normal n (unit, outwards), then Coulomb friction on the substep's displacement
// relative to the collider (d - m after the push): its tangential part is cancelled if it is at
// most mu times the push's depth along n (static friction), else shortened by that much
// (sliding). The depth is what the mass was pressed in over the substep (g cos(theta) dt^2 for a
// mass resting on a slope), so the friction is mu times the normal force at any substep length.
// The whole change, push and friction, is added to x once.
template <class R>
void coulomb_respond(const Vec3<R>& t_minus_x, const Vec3<R>& n, R mu, const Vec3<R>& m, Vec3<R>& x, Vec3<R>& d) {
  const Vec3<R> pushed = d + t_minus_x;
  const R depth = dot3(t_minus_x, n);
  Vec3<R> cancel(0);
  if (depth > R(0) && mu > R(0)) {
    const Vec3<R> rel = pushed - m;
    const Vec3<R> tangential = rel - n * dot3(rel, n);
    const R slide = length3(tangential);
    const R limit = mu * depth;
    if (slide > R(0)) cancel = slide <= limit ? tangential : tangential * (limit * (R(1) / slide));
  }
  x = x + (t_minus_x - cancel);
  d = pushed - cancel;
}

// A contact's response along the outward normal n: xpbd's Coulomb friction when `coulomb`,
// else the CS184 blend keeping `keep` (1: no friction), relative to the collider's motion.
template <class R>
void respond_to_contact(bool coulomb, const Vec3<R>& t_minus_x, const Vec3<R>& n, R keep, R mu, const Vec3<R>& motion,
                        Vec3<R>& x, Vec3<R>& d) {
  if (coulomb) coulomb_respond(t_minus_x, n, mu, motion, x, d);
  else if (motion != Vec3<R>(0)) blend_to_moving(t_minus_x, keep, motion, x, d);
  else blend_to(t_minus_x, keep, x, d);
}

// A mass against one mesh collider's field (reference_mesh_collisions.cpp): pushed out to
// `thickness` along the field's gradient, with the collider's friction (none when `friction` is
// false); and the same push without friction for a mass deeper than 0.1 mm (keep_out_of_mesh).
template <class R> void collide_with_mesh(const Constants<R>& c, const MeshColliderT<R>& m, bool friction, Vec3<R>& x, Vec3<R>& d);
template <class R> void keep_out_of_mesh(const Constants<R>& c, const MeshColliderT<R>& m, Vec3<R>& x, Vec3<R>& d);
// The field of `m` at local point p (sdf: Constants::sdf): false outside its grid.
template <class R> bool sample_mesh_field(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& p, R& phi, Vec3<R>& grad);
// The same at world point x (where m.origin puts the mesh).
template <class R> bool sample_mesh_at(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& x, R& phi, Vec3<R>& grad);
// A mesh collider's constants from its scene entry and its field, placed at p.origin; offset:
// its first node in the array the field is read from (Constants::sdf).
template <class R> MeshColliderT<R> make_mesh_collider(const MeshColliderParams& p, const SdfGrid& g, uint32_t offset);


}  // namespace clothsim

// The reference's collision passes (docs/design.md §1 steps 3-4): self-collision over the hashed
// grid and the spheres and planes, with the friction blend written on small differences.
#include "reference/reference.hpp"
#include "reference/reference_detail.hpp"

namespace clothsim {

template <class R> void collide_self(const Constants<R>& c, State<R>& s) {
  build_spatial_hash(s.pos, c.inv_cell, s.hash);
  resolve_self_contacts(c, s);
}

template <class R> void resolve_self_contacts(const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    s.pos_out[i] = s.pos[i];
    if (s.pos[i].w == R(0)) continue;
    const Vec3<R> xi(s.pos[i]);
    Vec3<R> sum(0);
    uint32_t hits = 0;
    for_each_neighbour(s.hash, s.pos, c.inv_cell, cell_of(xi, c.inv_cell), [&](uint32_t j) {
      const Vec3<R> e3 = xi - Vec3<R>(s.pos[j]);
      const R d = length3(e3);
      // i itself, and coincident masses, have no direction to separate along: skipped.
      if (d >= c.contact_distance || d == R(0)) return;
      if (!c.bounded_contact) {
        sum += e3 * ((c.contact_distance - d) * (R(1) / d));
        ++hits;
        return;
      }
      // Bounded contact: masses closer at rest than the contact distance (the cloth's own
      // neighbours) are kept only at their rest distance; each of the pair moves half the gap.
      const R rest = length3(c.rest[i] - c.rest[j]);
      const R keep = std::min(c.contact_distance, rest);
      if (!(d < keep)) return;
      sum += e3 * ((keep - d) * (R(0.5) / d));
      ++hits;
    });
    if (hits > 0) {
      // Classic: the average over the contacts, spread over the substeps (docs/design.md §1.3).
      // Bounded: the average, whole, every substep.
      const R scale = c.bounded_contact ? R(1) / R(hits) : R(1) / (R(hits) * c.steps);
      const Vec3<R> corr = sum * scale;
      s.pos_out[i] = Vec4<R>(xi + corr, s.pos[i].w);
      s.disp[i] = Vec4<R>(Vec3<R>(s.disp[i]) + corr, R(0));  // x_prev stays where it was
    }
  }
  s.pos.swap(s.pos_out);
}

// A moving sphere: e = x - o at the substep's end, e_prev = x_prev - o_prev = e - d + m at its
// start. A mass normally enters by at most its motion relative to the sphere per substep and
// is pushed out along e. Should that motion carry it past the centre (e . e_prev < 0, a
// sphere moving by more than its radius in one substep), pushing along e would pass it
// through: it is put back on the side it came from, along e_prev (no tunnelling at any speed).
template <class R> Vec3<R> moving_sphere_push(const Vec3<R>& e, R dist, R r, const Vec3<R>& d, const Vec3<R>& m) {
  const Vec3<R> e_prev = (e - d) + m;
  const R prev_dist = length3(e_prev);
  if (dot3(e, e_prev) < R(0) && prev_dist > R(0)) return e_prev * (r * (R(1) / prev_dist)) - e;
  return dist > R(0) ? e * ((r - dist) * (R(1) / dist)) : Vec3<R>(0, r, 0);
}

// A mass outside a sphere at the end of the substep, e = x - o (|e| = dist > r), that moved by
// rel = d - m relative to it: true if its path e - rel .. e went into the sphere deeper than
// 0.1 mm (a fast mass, or a fast sphere, passing through within the substep), with t - x the
// push back to where the path entered the surface. A mass that moved less than its distance
// to the surface cannot have entered: the common case costs one comparison.
template <class R> bool passed_through_sphere(const Vec3<R>& e, R dist, R r, const Vec3<R>& rel, Vec3<R>& t_minus_x) {
  const R gap = dist - r;
  const R a = dot3(rel, rel);
  if (!(a > gap * gap)) return false;
  const Vec3<R> e_prev = e - rel;
  const R b = dot3(e_prev, rel);  // the path is e_prev + s rel, s in [0, 1]
  if (!(b < R(0))) return false;  // moving away from the centre: leaving, not passing through
  const R s_closest = std::min(R(1), -b * (R(1) / a));
  const Vec3<R> closest = e_prev + rel * s_closest;
  const R depth = r - length3(closest);
  if (!(depth > R(1e-4))) return false;
  const R c = dot3(e_prev, e_prev) - r * r;
  if (c > R(0)) {
    const R s_in = (-b - std::sqrt(b * b - a * c)) * (R(1) / a);  // b^2 - ac > 0: the path meets it
    t_minus_x = (e_prev + rel * s_in) - e;
  } else {
    // It started on the surface (where the last contact put it) or inside: back out on its own side.
    const R prev_dist = length3(e_prev);
    t_minus_x = prev_dist > R(0) ? e_prev * (r * (R(1) / prev_dist)) - e : Vec3<R>(0, r, 0) - e;
  }
  return true;
}

// The friction blend moves a mass from x_prev towards the surface point t, and a chord between
// two points of a sphere runs inside it: a fast mass sliding over a sphere can end the blend
// deep inside. Deeper than 0.1 mm it is put back on the surface along e, without friction (the
// classic scenes never come near: their chords sink by under a micrometre).
template <class R> void keep_out_of_sphere(const SphereColliderT<R>& sp, Vec3<R>& x, Vec3<R>& d) {
  const Vec3<R> e = x - Vec3<R>(sp.origin_radius);
  const R dist = length3(e), radius = sp.origin_radius.w;
  if (!(radius - dist > R(1e-4)) || !(dist > R(0))) return;
  const Vec3<R> out = e * ((radius - dist) * (R(1) / dist));
  x = x + out;
  d = d + out;
}

// A mass deeper than 0.1 mm behind a plane's front goes to its surface offset on the front,
// along the normal, without friction: after Provot's pull, and after the CS184 blend of a mass
// found behind (the blend starts from x_prev, behind too, so it can end still behind).
template <class R> void keep_in_front_of_plane(const PlaneColliderT<R>& pl, Vec3<R>& x, Vec3<R>& d) {
  const Vec3<R> normal(pl.normal);
  const R front = pl.point.w;
  const R dist = dot3(x - Vec3<R>(pl.point), normal);
  if (!(dist * front < R(-1e-4))) return;
  const Vec3<R> out = normal * (R(1e-4) * front - dist);
  x = x + out;
  d = d + out;
}

// The outward normal of a sphere at the point x + t_minus_x (up at the centre).
template <class R> Vec3<R> sphere_normal(const SphereColliderT<R>& sp, const Vec3<R>& x, const Vec3<R>& t_minus_x) {
  const Vec3<R> e = (x + t_minus_x) - Vec3<R>(sp.origin_radius);
  const R len = length3(e);
  return len > R(0) ? e * (R(1) / len) : Vec3<R>(0, 1, 0);
}

// One sphere contact's response: xpbd's Coulomb friction (with friction on), else the CS184
// blend, in the sphere's frame when it moves.
template <class R>
void respond_to_sphere(const Constants<R>& c, bool friction, const SphereColliderT<R>& sp, const Vec3<R>& t_minus_x,
                       Vec3<R>& x, Vec3<R>& d) {
  const Vec3<R> motion(sp.motion);
  const R keep = sp.keep.x, mu = sp.keep.y;
  if (friction && c.xpbd) coulomb_respond(t_minus_x, sphere_normal(sp, x, t_minus_x), mu, motion, x, d);
  else if (motion != Vec3<R>(0)) blend_to_moving(t_minus_x, friction ? keep : R(1), motion, x, d);
  else blend_to(t_minus_x, friction ? keep : R(1), x, d);
}

// One particle against every sphere, then every plane, then every mesh. With `friction` false every contact
// keeps all of its tangential motion (keep = 1): the pure push-out of xpbd's constraint pass.
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction) {
  for (const SphereColliderT<R>& sp : c.spheres) {
    const Vec3<R> e = x - Vec3<R>(sp.origin_radius), motion(sp.motion);
    const R dist = length3(e), radius = sp.origin_radius.w;
    if (dist > radius) {
      // Outside at the end: caught if it went through the sphere during the substep.
      Vec3<R> t_minus_x;
      if (!passed_through_sphere(e, dist, radius, d - motion, t_minus_x)) continue;
      respond_to_sphere(c, friction, sp, t_minus_x, x, d);
      keep_out_of_sphere(sp, x, d);
      continue;
    }
    if (motion != Vec3<R>(0)) {
      respond_to_sphere(c, friction, sp, moving_sphere_push(e, dist, radius, d, motion), x, d);
      keep_out_of_sphere(sp, x, d);
      continue;
    }
    // t - x = e (r / |e| - 1): the push out to the surface (a mass exactly at the centre has no
    // outward direction: it goes up), unless it passed the centre this substep (a mass faster
    // than the sphere's radius per substep): then back out on its own side.
    const Vec3<R> e_prev = e - d;
    const R prev_dist = length3(e_prev);
    const Vec3<R> t_minus_x = dot3(e, e_prev) < R(0) && prev_dist > R(0) ? e_prev * (radius * (R(1) / prev_dist)) - e
                              : dist > R(0) ? e * ((radius - dist) * (R(1) / dist))
                                            : Vec3<R>(0, radius, 0);
    respond_to_sphere(c, friction, sp, t_minus_x, x, d);
    keep_out_of_sphere(sp, x, d);
  }
  for (const PlaneColliderT<R>& pl : c.planes) {
    const bool coulomb = friction && c.xpbd;
    const Vec3<R> point(pl.point), normal(pl.normal), motion(pl.motion);
    const R front = pl.point.w, keep = pl.normal.w, mu = pl.motion.w;
    // The classic test: a mass that crossed the plane this substep (dist * dist_prev <= 0; for
    // a moving plane in its frame, x_prev - p_prev = (x - p) - (d - m), so a sweep is seen at
    // any speed) goes back to the side it came from. And a mass found behind the plane's front
    // at both ends of the substep (a correction put it there) is lifted to the front. With
    // Coulomb friction a mass within the surface offset in front is in contact too: a mass
    // resting there is pressed in a little every substep, and held every substep.
    const R dist = dot3(x - point, normal);
    const R dist_prev = dist - dot3(d - motion, normal);
    R side;
    if (dist * dist_prev > R(0)) {
      if (!(dist * front < (coulomb ? R(1e-4) : R(0)))) continue;
      side = front;
    } else {
      side = dist_prev > R(0) ? R(1) : (dist_prev < R(0) ? R(-1) : R(0));
    }
    // t = x - dist n + SURFACE_OFFSET side n, so t - x is along n.
    const Vec3<R> t_minus_x = normal * (R(1e-4) * side - dist);
    respond_to_contact(coulomb, t_minus_x, normal * (side != R(0) ? side : front), friction ? keep : R(1),
                       mu, motion, x, d);
    if (side == front) keep_in_front_of_plane(pl, x, d);
  }
  for (const MeshColliderT<R>& m : c.meshes) collide_with_mesh(c, m, friction, x, d);
}

template <class R> void keep_out_of_colliders(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d) {
  for (const SphereColliderT<R>& sp : c.spheres) keep_out_of_sphere(sp, x, d);
  for (const PlaneColliderT<R>& pl : c.planes) keep_in_front_of_plane(pl, x, d);
  for (const MeshColliderT<R>& m : c.meshes) keep_out_of_mesh(c, m, x, d);
}

template <class R> void collide_objects(const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    if (s.pos[i].w == R(0)) continue;
    Vec3<R> x(s.pos[i]), d(s.disp[i]);
    collide_particle(c, x, d, true);
    s.pos[i] = Vec4<R>(x, s.pos[i].w);
    s.disp[i] = Vec4<R>(d, R(0));
  }
}

#define CLOTHSIM_INSTANTIATE(R) \
  template void collide_self<R>(const Constants<R>&, State<R>&); \
  template void resolve_self_contacts<R>(const Constants<R>&, State<R>&); \
  template void collide_objects<R>(const Constants<R>&, State<R>&); \
  template void collide_particle<R>(const Constants<R>&, Vec3<R>&, Vec3<R>&, bool); \
  template void keep_out_of_colliders<R>(const Constants<R>&, Vec3<R>&, Vec3<R>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

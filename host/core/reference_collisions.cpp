// The reference's collision passes (DESIGN.md §1 steps 3-4): self-collision over the hashed
// grid and the spheres and planes, with the friction blend written on small differences.
#include "reference.hpp"
#include "reference_detail.hpp"

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
      sum += e3 * ((c.contact_distance - d) * (R(1) / d));
      ++hits;
    });
    if (hits > 0) {
      const Vec3<R> corr = sum * (R(1) / (R(hits) * c.steps));
      s.pos_out[i] = Vec4<R>(xi + corr, s.pos[i].w);
      s.disp[i] = Vec4<R>(Vec3<R>(s.disp[i]) + corr, R(0));  // x_prev stays where it was
    }
  }
  s.pos.swap(s.pos_out);
}

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

// One particle against every sphere, then every plane. With `friction` false every contact
// keeps all of its tangential motion (keep = 1): the pure push-out of xpbd's constraint pass.
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction) {
  for (const SphereC<R>& sp : c.spheres) {
    const Vec3<R> e = x - sp.origin;
    const R dist = length3(e);
    if (dist > sp.radius) continue;
    const R keep = friction ? sp.keep : R(1);
    if (sp.motion != Vec3<R>(0)) {
      blend_to_moving(moving_sphere_push(e, dist, sp.radius, d, sp.motion), keep, sp.motion, x, d);
      continue;
    }
    // t - x = e (r / |e| - 1): the push out to the surface. A mass exactly at the centre
    // has no outward direction: it goes up.
    const Vec3<R> t_minus_x = dist > R(0) ? e * ((sp.radius - dist) * (R(1) / dist)) : Vec3<R>(0, sp.radius, 0);
    blend_to(t_minus_x, keep, x, d);
  }
  for (const PlaneC<R>& pl : c.planes) {
    const R keep = friction ? pl.keep : R(1);
    if (pl.motion != Vec3<R>(0)) {
      // The side test in the plane's frame: x_prev - p_prev = (x - p) - (d - m). It sees a
      // plane that swept over a mass at any speed.
      const R dist = dot3(x - pl.point, pl.normal);
      const R dist_prev = dist - dot3(d - pl.motion, pl.normal);
      if (dist * dist_prev > R(0)) continue;
      const R side = dist_prev > R(0) ? R(1) : (dist_prev < R(0) ? R(-1) : R(0));
      blend_to_moving(pl.normal * (R(1e-4) * side - dist), keep, pl.motion, x, d);
      continue;
    }
    const R dist = dot3(x - pl.point, pl.normal);
    const R dist_prev = dist - dot3(d, pl.normal);  // (x_prev - p) . n
    if (dist * dist_prev > R(0)) continue;
    const R side = dist_prev > R(0) ? R(1) : (dist_prev < R(0) ? R(-1) : R(0));
    // t = x - dist n + SURFACE_OFFSET side n, so t - x is along n.
    blend_to(pl.normal * (R(1e-4) * side - dist), keep, x, d);
  }
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
  template void collide_particle<R>(const Constants<R>&, Vec3<R>&, Vec3<R>&, bool);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

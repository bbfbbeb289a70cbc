// The reference's collision passes (docs/design.md §1 steps 3-4): self-collision over the hashed
// grid and the spheres and planes, with the friction blend written on small differences.
#include "reference/reference.hpp"
#include "reference/reference_detail.hpp"
#include "reference/reference_skinning.hpp"
#include "../../../compute/shared/self_contact.glsl"
#include "../../../compute/shared/springs.glsl"

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
      if (c.welds && c.weld[i] == c.weld[j]) return;  // a sewn pair: its seam holds it together
      if (!c.bounded_contact) {
        sum = shared::add_self_contact(sum, e3, d, c.contact_distance, R(1));
        ++hits;
        return;
      }
      // Bounded contact: masses closer at rest than the contact distance (the cloth's own
      // neighbours) are kept only at their rest distance; each of the pair moves half the gap.
      const R keep = shared::bounded_keep(c.rest[i], c.rest[j], c.contact_distance);
      if (!(d < keep)) return;
      sum = shared::add_self_contact(sum, e3, d, keep, R(0.5));
      ++hits;
    });
    if (hits > 0) {
      // Classic: the average over the contacts, spread over the substeps (docs/design.md §1.3).
      // Bounded: the average, whole, every substep.
      const Vec3<R> corr = sum * shared::self_contact_scale(hits, c.bounded_contact, c.steps);
      s.pos_out[i] = Vec4<R>(xi + corr, s.pos[i].w);
      s.disp[i] = Vec4<R>(Vec3<R>(s.disp[i]) + corr, R(0));  // x_prev stays where it was
    }
  }
  s.pos.swap(s.pos_out);
}

// relax_vertices.comp's add_self_contacts: mass i's contacts with the masses of other colours in
// the buckets of the 27 cells around x, each bucket once (a later row skips the buckets of an
// earlier row's run), with no filter by cell: the distance test drops the far ones.
template <class R>
void add_self_contacts(const Constants<R>& c, const State<R>& s, uint32_t i, const Vec3<R>& x, const Vec3<R>& start_i,
                       Vec3<R>& f, shared::Sym3<R>& hess) {
  const R k = R(SELF_CONTACT_STIFFNESS) * c.particle_ks[i];  // as the shader's, from the material's ks
  const std::vector<uint32_t>& colour = c.hierarchy->fine_colour;
  const uint32_t own = colour[i];
  const glm::ivec3 cell = cell_of(x, c.inv_cell);
  const uint32_t mask = s.hash.table_size - 1u;
  uint32_t runs[9];
  for (int r = 0; r < 9; ++r) {
    runs[r] = (hash_row(cell.y + r % 3 - 1, cell.z + r / 3 - 1) + uint32_t(cell.x - 1)) & mask;
    for (uint32_t dx = 0; dx < 3; ++dx) {
      const uint32_t b = (runs[r] + dx) & mask;
      bool taken = false;
      for (int q = 0; q < r; ++q) taken = taken || ((b - runs[q]) & mask) < 3u;
      if (taken) continue;
      for (uint32_t e = s.hash.start[b]; e < s.hash.start[b + 1]; ++e) {
        const uint32_t j = s.hash.entries[e];
        const Vec3<R> e3 = x - Vec3<R>(s.pos[j]);
        const R d = length3(e3);
        if (d >= c.contact_distance || d == R(0) || colour[j] == own) continue;
        const Vec3<R> start_j = Vec3<R>(s.pos[j]) - Vec3<R>(s.disp[j]);
        const R keep = shared::sweep_contact_keep(start_i - start_j, c.contact_distance);
        if (d >= keep) continue;
        if (c.welds && c.weld[i] == c.weld[j]) continue;  // a sewn pair
        if (!shared::apart_at_rest(c.rest[i], c.rest[j], c.contact_distance)) continue;  // neighbours
        Vec3<R> n;
        f = shared::add_self_contact_pull(f, e3, d, keep, k, n);
        shared::add_spring_hessian(hess, n, k, R(0));
      }
    }
  }
}

// One particle against every sphere, then every plane, then every mesh. With `friction` false every contact
// keeps all of its tangential motion (keep = 1): the pure push-out after a sweep that moved a mass into a collider that moves.
// The formulas are compute/shared/collisions.glsl's.
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction, uint32_t* slots,
                                         bool search, bool still_only) {
  const bool coulomb = friction && c.multigrid;  // the plane's contact test (resting contact)
  for (const SphereColliderT<R>& sp : c.control.spheres) {
    const Vec3<R> origin(sp.origin_radius), motion(sp.motion);
    const R radius = sp.origin_radius.w, keep = sp.keep.x, mu = sp.keep.y;
    const Vec3<R> e = x - origin;
    const R dist = length3(e);
    Vec3<R> t_minus_x;
    if (dist > radius) {
      // Outside at the end: caught if it went through the sphere during the substep.
      if (!passed_through_sphere(e, dist, radius, d - motion, t_minus_x)) continue;
    } else if (motion != Vec3<R>(0)) {
      t_minus_x = moving_sphere_push(e, dist, radius, d, motion);
    } else {
      t_minus_x = static_sphere_push(e, dist, radius, d);
    }
    const bool held = shared::takes_friction(friction, still_only, motion);
    respond_to_sphere(held && c.multigrid, origin, held ? keep : R(1), mu, motion, t_minus_x, x, d);
    keep_out_of_sphere(origin, radius, x, d);
  }
  for (const PlaneColliderT<R>& pl : c.control.planes) {
    // The classic test: a mass that crossed the plane this substep (dist * dist_prev <= 0; for
    // a moving plane in its frame, x_prev - p_prev = (x - p) - (d - m), so a sweep is seen at
    // any speed) goes back to the side it came from. And a mass found behind the plane's front
    // at both ends of the substep (a correction put it there) is lifted to the front. With
    // Coulomb friction a mass within the surface offset in front is in contact too: a mass
    // resting there is pressed in a little every substep, and held every substep.
    const Vec3<R> point(pl.point), normal(pl.normal), motion(pl.motion);
    const R front = pl.point.w, keep = pl.normal.w, mu = pl.motion.w;
    R dist, dist_prev;
    const bool crossed = plane_sides(x, d, point, normal, motion, dist, dist_prev);
    if (!crossed && stays_in_front(dist, front, coulomb)) continue;
    const R side = plane_side(crossed, dist_prev, front);
    const bool held = shared::takes_friction(friction, still_only, motion);
    respond_to_plane(held && c.multigrid, normal, front, held ? keep : R(1), mu, motion, dist, side, x, d);
    if (side == front) keep_in_front_of_plane(point, normal, front, x, d);
  }
  MeshColliderT<R> frame;  // a skinned collider's, at this mass
  for (const MeshColliderT<R>& m : c.control.meshes)
    if (const MeshColliderT<R>* at = mesh_at(c, m, x, d, frame, slots, search))
      collide_with_mesh(c, *at, shared::takes_friction(friction, still_only, Vec3<R>(at->motion)), x, d);
}

template <class R> void keep_out_of_colliders(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, uint32_t* slots) {
  for (const SphereColliderT<R>& sp : c.control.spheres) keep_out_of_sphere(Vec3<R>(sp.origin_radius), sp.origin_radius.w, x, d);
  for (const PlaneColliderT<R>& pl : c.control.planes) keep_in_front_of_plane(Vec3<R>(pl.point), Vec3<R>(pl.normal), pl.point.w, x, d);
  MeshColliderT<R> frame;
  for (const MeshColliderT<R>& m : c.control.meshes)
    if (const MeshColliderT<R>* at = mesh_at(c, m, x, d, frame, slots, false)) keep_out_of_mesh(c, *at, x, d);
}

template <class R> void collide_objects(const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    if (s.pos[i].w == R(0)) continue;
    Vec3<R> x(s.pos[i]), d(s.disp[i]);
    collide_particle(c, x, d, true, skin_slots(c, s, uint32_t(i)), true);  // the substep's first: a search
    s.pos[i] = Vec4<R>(x, s.pos[i].w);
    s.disp[i] = Vec4<R>(d, R(0));
  }
}

#define CLOTHSIM_INSTANTIATE(R) \
  template void collide_self<R>(const Constants<R>&, State<R>&); \
  template void resolve_self_contacts<R>(const Constants<R>&, State<R>&); \
  template void add_self_contacts<R>(const Constants<R>&, const State<R>&, uint32_t, const Vec3<R>&, const Vec3<R>&, Vec3<R>&, \
                                     shared::Sym3<R>&); \
  template void collide_objects<R>(const Constants<R>&, State<R>&); \
  template void collide_particle<R>(const Constants<R>&, Vec3<R>&, Vec3<R>&, bool, uint32_t*, bool, bool); \
  template void keep_out_of_colliders<R>(const Constants<R>&, Vec3<R>&, Vec3<R>&, uint32_t*);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

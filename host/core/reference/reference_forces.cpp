// The reference's force, integration and normal passes (docs/design.md §1 steps 1-2, the wind, fabric's
// predict): one function per pass, each the twin of the compute shader of the same name.
#include "reference/reference.hpp"
#include "../../../compute/shared/integration.glsl"
#include "../../../compute/shared/springs.glsl"
#include "../../../compute/shared/wind.glsl"

namespace clothsim {

// The share of one corner in the aerodynamic force on triangle (a, b, c), from its corners'
// positions and displacements (docs/model.md, "Wind"; the formulas are compute/shared/wind.glsl's).
template <class R>
Vec3<R> triangle_wind_share(const layout::StepParamsT<R>& w, R gust_phase, const Vec3<R>& pa, const Vec3<R>& pb, const Vec3<R>& pc,
                            const Vec3<R>& da, const Vec3<R>& db, const Vec3<R>& dc) {
  const Vec3<R> air = shared::air_velocity(w.gust_enabled != 0u, w.wind_velocity, w.gust_velocity, gust_phase,
                                           w.wind_direction, w.gust_inv_length3, pa, pb, pc);
  return shared::triangle_wind_share(pa, pb, pc, (da + db) + dc, air, w.wind_inv_3dt, w.wind_drag, w.wind_lift);
}

// Calls visit(t) for each triangle that has particle i as a corner, in ascending order (on a
// grid: the cells (x-1..x, y-1..y), each split into (A, C, B) and (B, C, D)). compute_normals
// and compute_wind_forces gather over them, as their shaders do.
template <class Visit> void for_each_triangle_around(const ClothModel& m, uint32_t i, Visit&& visit) {
  for (uint32_t k = m.corner_start[i]; k < m.corner_start[i + 1]; ++k) {
    const auto& t = m.triangles[m.corner_triangles[k]];
    const int tri[3] = {int(t[0]), int(t[1]), int(t[2])};
    visit(tri);
  }
}

template <class R> void compute_wind_forces(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  s.wind.resize(s.pos.size());
  for (uint32_t self = 0; self < uint32_t(m.count()); ++self) {
    Vec3<R> f(0);
    for_each_triangle_around(m, self, [&](const int (&t)[3]) {
      f += triangle_wind_share(c.params(), c.control.gust_phase, Vec3<R>(s.pos[t[0]]), Vec3<R>(s.pos[t[1]]), Vec3<R>(s.pos[t[2]]),
                               Vec3<R>(s.disp[t[0]]), Vec3<R>(s.disp[t[1]]), Vec3<R>(s.disp[t[2]]));
    });
    s.wind[self] = Vec4<R>(f, R(0));
  }
}

template <class R> void accumulate_forces(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  for (uint32_t i = 0; i < uint32_t(m.count()); ++i) {
    const Vec3<R> xi(s.pos[i]);
    Vec3<R> f = c.gravity * c.mass[i];
    // The particle's springs in the model's gather order (the grid's: kGatherOrder).
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
      const Spring& sp = m.springs[m.gather[g]];
      if (!c.enabled(sp)) continue;
      const uint32_t j = sp.i == i ? sp.j : sp.i;
      f = shared::add_spring_force(f, Vec3<R>(s.pos[j]) - xi, c.rest_of(sp), c.stiffness_of(m, sp));
    }
    if (c.has_attachments() && c.attach[i].w != R(0))  // after the springs, as forces.glsl adds it
      f = shared::add_anchor_pull(f, xi, Vec3<R>(c.attach[i]), c.attached_origin(i), c.attach[i].w);
    if (c.wind_enabled) f += Vec3<R>(s.wind[i]);  // after the springs, as advance.comp adds it
    s.force[i] = Vec4<R>(f, R(0));
  }
}

// A pinned mass keeps its position, or with pinned_motion goes to its anchor + the offset at
// the substep's end, and its displacement is that move (its velocity, for the springs'
// constraints, friction and the wind), as move_pinned in compute/pinned_motion.glsl.
// Where pinned mass k is at the end of this substep, if it follows pinned_motion.
template <class R> bool moving_pin_position(const Constants<R>& c, size_t k, Vec3<R>& x) {
  if (!c.moving_pins() || c.anchors[k].w == R(0)) return false;
  x = shared::pin_target(Vec3<R>(c.anchors[k]), c.control.pin_offset);
  return true;
}

template <class R> void move_pinned(const Constants<R>& c, size_t i, State<R>& s) {
  Vec3<R> next;
  if (!moving_pin_position(c, i, next)) return;
  s.disp[i] = Vec4<R>(next - Vec3<R>(s.pos[i]), R(0));
  s.pos[i] = Vec4<R>(next, s.pos[i].w);
}

template <class R> void integrate(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const R keep = c.materials[m.material[i]].keep_velocity;
    const R w = s.pos[i].w;
    if (w == R(0)) {
      move_pinned(c, i, s);
      continue;
    }
    // x' = x + (1 - damping) (x - x_prev) + a dt^2, with d = x - x_prev kept as its own vector.
    const Vec3<R> d = shared::verlet_move(Vec3<R>(s.disp[i]), keep, Vec3<R>(s.force[i]), w, c);
    s.disp[i] = Vec4<R>(d, R(0));
    s.pos[i] = Vec4<R>(Vec3<R>(s.pos[i]) + d, w);
  }
}

template <class R> void predict(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  if (s.offset.size() != s.pos.size()) s.offset.assign(s.pos.size(), Vec4<R>(0));
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const R w = s.pos[i].w;
    if (w == R(0)) {
      move_pinned(c, i, s);
      s.offset[i] = Vec4<R>(0);
      continue;
    }
    Vec3<R> acc = c.gravity;
    if (c.wind_enabled) acc = acc + Vec3<R>(s.wind[i]) * w;  // compute_wind_forces ran before
    Vec3<R> d = shared::predicted_move(Vec3<R>(s.disp[i]), c.materials[m.material[i]].keep_velocity, acc, c);
    if (c.max_step > R(0)) d = shared::limit_step(d, c.max_step);  // the bounded contact's speed limit
    const Vec3<R> x = Vec3<R>(s.pos[i]) + d;
    // The multigrid solve starts from the inertial position without the external forces' share
    // and applies it with the springs, so a cloth at rest starts where it rests and stays
    // exactly there (docs/model.md). The contacts still see the full prediction (Coulomb
    // friction takes its depth from it); prolong_to_cloth moves the masses by the offset.
    s.offset[i] = Vec4<R>(shared::solve_start_offset(acc, Vec3<R>(s.offset[i]), c.start_ks[i] * w, c), R(0));
    s.disp[i] = Vec4<R>(d, R(0));
    s.pos[i] = Vec4<R>(x, w);
  }
}

template <class R> void compute_normals(const ClothModel& m, State<R>& s) {
  for (uint32_t i = 0; i < uint32_t(m.count()); ++i) {
    Vec3<R> sum(0);
    for_each_triangle_around(m, i, [&](const int (&t)[3]) {
      const Vec3<R> p0(s.pos[t[0]]), p1(s.pos[t[1]]), p2(s.pos[t[2]]);
      // Unnormalised cross product: its length is twice the area, so this is area-weighted.
      sum += shared::cross3(p1 - p0, p2 - p0);
    });
    s.normal[i] = Vec4<R>(shared::unit_or_up(sum), R(0));
  }
}

// compute/limit_speed.comp
template <class R> void limit_speed(const ClothModel&, const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const Vec4<R> p = s.pos[i], d = s.disp[i];
    if (p.w == R(0) || !(length3(Vec3<R>(d)) > c.max_move)) continue;
    Vec3<R> x(p), moved(d);
    shared::limit_speed_of(x, moved, c.max_move);
    s.pos[i] = Vec4<R>(x, p.w);
    s.disp[i] = Vec4<R>(moved, d.w);
  }
}

#define CLOTHSIM_INSTANTIATE(R) \
  template void compute_wind_forces<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void accumulate_forces<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void integrate<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void predict<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void compute_normals<R>(const ClothModel&, State<R>&); \
  template void limit_speed<R>(const ClothModel&, const Constants<R>&, State<R>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

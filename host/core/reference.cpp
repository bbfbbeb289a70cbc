#include "reference.hpp"

#include <numeric>

namespace clothsim {

template <class R> Constants<R> make_constants(const Scene& scene, const ClothModel& model) {
  const ClothParams& cp = scene.cloth;
  const SimulationParams& sp = scene.simulation;
  Constants<R> c;
  const double dt = scene.dt();
  // Derived values are formed in double and rounded once, identically for the GPU upload.
  c.gravity = Vec3<R>(sp.gravity);
  c.mass = R(particle_mass(cp));  // from the scene, so a live density edit takes effect
  (void)model;
  c.ks = R(cp.ks);
  c.ks_bending = R(0.2 * cp.ks);
  c.keep_velocity = R(1.0 - cp.damping / 100.0);
  c.dt2 = R(dt * dt);
  c.stretch_limit = R(1.0 + sp.max_stretch);
  c.contact_distance = R(2.0 * cp.thickness);
  c.inv_cell = R(1.0 / (2.0 * cp.thickness));
  c.steps = R(sp.simulation_steps);
  // 1 / (ks dt^2): ks = 0 gives +inf, a constraint that never pulls.
  c.alpha = R(1.0 / (cp.ks * dt * dt));
  c.alpha_bending = R(1.0 / (0.2 * cp.ks * dt * dt));
  c.xpbd = sp.solver == Solver::Xpbd;
  c.tether_limit = R(1.0 + sp.tether_stretch);
  c.enabled[0] = cp.enable_structural;
  c.enabled[1] = cp.enable_shearing;
  c.enabled[2] = cp.enable_bending;
  c.iterations = sp.constraint_iterations;
  c.self_collision = sp.self_collision;
  for (auto& s : scene.spheres) c.spheres.push_back({Vec3<R>(s.origin), R(s.radius), R(1.0 - s.friction)});
  for (auto& p : scene.planes) c.planes.push_back({Vec3<R>(p.point), Vec3<R>(p.normal), R(1.0 - p.friction)});
  return c;
}

template <class R> State<R> initial_state(const ClothModel& m) {
  State<R> s;
  const int n = m.count();
  s.pos.resize(n);
  for (int i = 0; i < n; ++i)
    s.pos[i] = Vec4<R>(Vec3<R>(m.initial[i]), m.pinned[i] ? R(0) : R(1.0 / m.mass));
  s.disp.assign(n, Vec4<R>(0));  // at rest
  s.force.assign(n, Vec4<R>(0));
  s.normal.assign(n, Vec4<R>(0));
  s.pos_out = s.pos;
  s.hash = make_spatial_hash(uint32_t(n));
  return s;
}

// Rest length of spring `ref` seen from (x, y), or 0 when it leaves the grid.
inline double rest_of(const ClothModel& m, int x, int y, const SpringRef& ref, int* j) {
  const Direction& d = kDirections[ref.direction];
  int x2 = x + ref.sign * d.dx, y2 = y + ref.sign * d.dy;
  if (!in_grid(x2, y2, m.nw, m.nh)) return 0;
  *j = m.index(x2, y2);
  return ref.sign > 0 ? m.rest[m.index(x, y)][ref.direction] : m.rest[*j][ref.direction];
}

template <class R> void accumulate_forces(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x) {
      const int i = m.index(x, y);
      const Vec3<R> xi(s.pos[i]);
      Vec3<R> f = c.gravity * c.mass;
      for (const SpringRef& ref : kGatherOrder) {
        const Direction& d = kDirections[ref.direction];
        int j = -1;
        const R rest = R(rest_of(m, x, y, ref, &j));
        if (j < 0 || !c.enabled[int(d.type)]) continue;
        const R k = d.type == SpringType::Bending ? c.ks_bending : c.ks;
        const Vec3<R> e = Vec3<R>(s.pos[j]) - xi;
        const R len = length3(e);
        if (len > R(0)) {
          // Divisions are written as x * (1 / y): the GLSL compiler lowers a / b that way.
          const R inv = R(1) / len;
          f += e * (k * (len - rest) * inv);
        }
      }
      s.force[i] = Vec4<R>(f, R(0));
    }
}

template <class R> void integrate(const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const R w = s.pos[i].w;
    if (w == R(0)) continue;  // pinned: keeps its position
    const Vec3<R> a = Vec3<R>(s.force[i]) * w;
    // x' = x + (1 - damping) (x - x_prev) + a dt^2, with d = x - x_prev kept as its own vector.
    const Vec3<R> d = Vec3<R>(s.disp[i]) * c.keep_velocity + a * c.dt2;
    s.disp[i] = Vec4<R>(d, R(0));
    s.pos[i] = Vec4<R>(Vec3<R>(s.pos[i]) + d, w);
  }
}

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

template <class R> void collide_objects(const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    if (s.pos[i].w == R(0)) continue;
    Vec3<R> x(s.pos[i]), d(s.disp[i]);
    for (const SphereC<R>& sp : c.spheres) {
      const Vec3<R> e = x - sp.origin;
      const R dist = length3(e);
      if (dist > sp.radius) continue;
      // t - x = e (r / |e| - 1): the push out to the surface. A mass exactly at the centre
      // has no outward direction: it goes up.
      const Vec3<R> t_minus_x = dist > R(0) ? e * ((sp.radius - dist) * (R(1) / dist)) : Vec3<R>(0, sp.radius, 0);
      blend_to(t_minus_x, sp.keep, x, d);
    }
    for (const PlaneC<R>& pl : c.planes) {
      const R dist = dot3(x - pl.point, pl.normal);
      const R dist_prev = dist - dot3(d, pl.normal);  // (x_prev - p) . n
      if (dist * dist_prev > R(0)) continue;
      const R side = dist_prev > R(0) ? R(1) : (dist_prev < R(0) ? R(-1) : R(0));
      // t = x - dist n + SURFACE_OFFSET side n, so t - x is along n.
      blend_to(pl.normal * (R(1e-4) * side - dist), pl.keep, x, d);
    }
    s.pos[i] = Vec4<R>(x, s.pos[i].w);
    s.disp[i] = Vec4<R>(d, R(0));
  }
}

template <class R>
void solve_length_constraint_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s) {
  const int dir = colour / 2;
  const Direction& d = kDirections[dir];
  if (!c.enabled[int(d.type)]) return;
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x) {
      if (spring_colour(dir, x, y) != colour || !in_grid(x + d.dx, y + d.dy, m.nw, m.nh)) continue;
      const int i = m.index(x, y), j = m.index(x + d.dx, y + d.dy);
      const R wi = s.pos[i].w, wj = s.pos[j].w, wsum = wi + wj;
      if (wsum == R(0)) continue;
      const Vec3<R> xi(s.pos[i]), xj(s.pos[j]);
      const Vec3<R> e = xj - xi;
      const R len = length3(e);
      const R limit = c.stretch_limit * R(m.rest[i][dir]);
      if (!(len > limit)) continue;
      const Vec3<R> corr = e * ((len - limit) * (R(1) / len));
      const R inv_wsum = R(1) / wsum;
      const Vec3<R> ci = corr * (wi * inv_wsum), cj = corr * (wj * inv_wsum);
      s.pos[i] = Vec4<R>(xi + ci, wi);
      s.pos[j] = Vec4<R>(xj - cj, wj);
      // A pinned end (w = 0) gets a zero correction: its displacement stays as it is.
      s.disp[i] = Vec4<R>(Vec3<R>(s.disp[i]) + ci, R(0));
      s.disp[j] = Vec4<R>(Vec3<R>(s.disp[j]) - cj, R(0));
    }
}

template <class R> void solve_length_constraints(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  for (int it = 0; it < c.iterations; ++it)
    for (int colour = 0; colour < NUM_COLOURS; ++colour) solve_length_constraint_colour(m, c, colour, s);
}

template <class R> void predict(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const R w = s.pos[i].w;
    if (w == R(0)) continue;  // pinned: keeps its position (and is never written: tethers read it)
    Vec3<R> d = Vec3<R>(s.disp[i]) * c.keep_velocity + c.gravity * c.dt2;
    Vec3<R> x = Vec3<R>(s.pos[i]) + d;
    if (const int pin = m.tether_pin[i]; pin >= 0) {
      const Vec3<R> e = x - Vec3<R>(s.pos[pin]);
      const R len = length3(e);
      const R limit = c.tether_limit * R(m.tether_rest[i]);
      if (len > limit) {
        const Vec3<R> corr = e * ((limit - len) * (R(1) / len));
        x = x + corr;
        d = d + corr;
      }
    }
    s.disp[i] = Vec4<R>(d, R(0));
    s.pos[i] = Vec4<R>(x, w);
  }
}

template <class R>
void solve_distance_constraint_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s) {
  const int dir = colour / 2;
  const Direction& d = kDirections[dir];
  if (!c.enabled[int(d.type)]) return;
  const R alpha = d.type == SpringType::Bending ? c.alpha_bending : c.alpha;
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x) {
      if (spring_colour(dir, x, y) != colour || !in_grid(x + d.dx, y + d.dy, m.nw, m.nh)) continue;
      const int i = m.index(x, y), j = m.index(x + d.dx, y + d.dy);
      const R wi = s.pos[i].w, wj = s.pos[j].w, wsum = wi + wj;
      if (wsum == R(0)) continue;
      const R rest = R(m.rest[i][dir]);
      Vec3<R> xi(s.pos[i]), xj(s.pos[j]), di(s.disp[i]), dj(s.disp[j]);
      Vec3<R> e = xj - xi;
      R len = length3(e);
      if (len > R(0)) {
        // XPBD with the multiplier starting at 0 (one solve per substep): dlambda = -C / (w + alpha~),
        // C = len - rest, moving i by -wi grad_i C dlambda and j by -wj grad_j C dlambda.
        const Vec3<R> corr = e * ((len - rest) * (R(1) / len) * (R(1) / (wsum + alpha)));
        const Vec3<R> ci = corr * wi, cj = corr * wj;
        xi = xi + ci;
        xj = xj - cj;
        di = di + ci;
        dj = dj - cj;
        e = xj - xi;
        len = length3(e);
      }
      // max_stretch stays a hard limit: Provot's projection, as in solve_length_constraints.
      const R limit = c.stretch_limit * rest;
      if (len > limit) {
        const Vec3<R> corr = e * ((len - limit) * (R(1) / len));
        const R inv_wsum = R(1) / wsum;
        const Vec3<R> ci = corr * (wi * inv_wsum), cj = corr * (wj * inv_wsum);
        xi = xi + ci;
        xj = xj - cj;
        di = di + ci;
        dj = dj - cj;
      }
      s.pos[i] = Vec4<R>(xi, wi);
      s.pos[j] = Vec4<R>(xj, wj);
      s.disp[i] = Vec4<R>(di, R(0));
      s.disp[j] = Vec4<R>(dj, R(0));
    }
}

template <class R> void solve_distance_constraints(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  for (int colour = 0; colour < NUM_COLOURS; ++colour) solve_distance_constraint_colour(m, c, colour, s);
}

template <class R> void compute_normals(const ClothModel& m, State<R>& s) {
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x) {
      Vec3<R> sum(0);
      // The up to four cells around (x, y), each split into (A, C, B) and (B, C, D).
      for (int cy = y - 1; cy <= y; ++cy)
        for (int cx = x - 1; cx <= x; ++cx) {
          if (cx < 0 || cy < 0 || cx + 1 >= m.nw || cy + 1 >= m.nh) continue;
          const int a = m.index(cx, cy), b = m.index(cx + 1, cy), cc = m.index(cx, cy + 1), dd = m.index(cx + 1, cy + 1);
          const int tris[2][3] = {{a, cc, b}, {b, cc, dd}};
          const int self = m.index(x, y);
          for (auto& t : tris) {
            if (t[0] != self && t[1] != self && t[2] != self) continue;
            const Vec3<R> p0(s.pos[t[0]]), p1(s.pos[t[1]]), p2(s.pos[t[2]]);
            const Vec3<R> u = p1 - p0, v = p2 - p0;
            // Unnormalised cross product: its length is twice the area, so this is area-weighted.
            sum += Vec3<R>(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
          }
        }
      const R len = length3(sum);
      s.normal[m.index(x, y)] = len > R(0) ? Vec4<R>(sum * (R(1) / len), R(0)) : Vec4<R>(0, 1, 0, 0);
    }
}

#define CLOTHSIM_INSTANTIATE(R)                                                                         \
  template Constants<R> make_constants<R>(const Scene&, const ClothModel&);                           \
  template State<R> initial_state<R>(const ClothModel&);                                              \
  template void accumulate_forces<R>(const ClothModel&, const Constants<R>&, State<R>&);              \
  template void integrate<R>(const Constants<R>&, State<R>&);                                         \
  template void collide_self<R>(const Constants<R>&, State<R>&);                                      \
  template void resolve_self_contacts<R>(const Constants<R>&, State<R>&);                             \
  template void collide_objects<R>(const Constants<R>&, State<R>&);                                   \
  template void solve_length_constraint_colour<R>(const ClothModel&, const Constants<R>&, int, State<R>&); \
  template void solve_length_constraints<R>(const ClothModel&, const Constants<R>&, State<R>&);       \
  template void compute_normals<R>(const ClothModel&, State<R>&);                                     \
  template void predict<R>(const ClothModel&, const Constants<R>&, State<R>&);                                           \
  template void solve_distance_constraint_colour<R>(const ClothModel&, const Constants<R>&, int, State<R>&); \
  template void solve_distance_constraints<R>(const ClothModel&, const Constants<R>&, State<R>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

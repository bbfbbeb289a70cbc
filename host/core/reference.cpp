#include "reference.hpp"

#include <numeric>

#include "motion.hpp"

namespace clothsim {

bool Timeline::moves() const {
  for (auto& k : spheres) if (k) return true;
  for (auto& k : planes) if (k) return true;
  return pins.has_value() || gust_period > 0;
}

namespace {

template <class R> void make_wind(const Scene& scene, Constants<R>& c) {
  if (!scene.wind) return;
  const WindParams& w = *scene.wind;
  WindC<R>& wc = c.wind;
  wc.enabled = true;
  wc.velocity = Vec3<R>(w.velocity);
  wc.drag = R(-w.air_density * w.drag_coefficient / 12.0);
  wc.lift = R(-w.air_density * w.lift_coefficient / 12.0);
  wc.inv_3dt = R(1.0 / (3.0 * scene.dt()));
  const double speed = std::sqrt(w.velocity.x * w.velocity.x + w.velocity.y * w.velocity.y + w.velocity.z * w.velocity.z);
  // Gusts need a direction to travel along: none in still air.
  if (w.gust && w.gust->strength > 0 && speed > 0) {
    wc.gusts = true;
    wc.gust_velocity = Vec3<R>(w.velocity * w.gust->strength);
    wc.direction = Vec3<R>(w.velocity / speed);
    wc.gust_inv_length3 = R(1.0 / (3.0 * w.gust->length));
    c.timeline.gust_period = w.gust->period;
  }
}

template <class R> void make_timeline(const Scene& scene, const ClothModel& model, Constants<R>& c) {
  Timeline& tl = c.timeline;
  tl.dt = scene.dt();
  for (auto& s : scene.spheres) tl.spheres.push_back(s.motion ? std::optional(s.motion->keyframes) : std::nullopt);
  for (auto& p : scene.planes) tl.planes.push_back(p.motion ? std::optional(p.motion->keyframes) : std::nullopt);
  if (scene.cloth.pinned_motion) {
    tl.pins = scene.cloth.pinned_motion->keyframes;
    for (int i = 0; i < model.count(); ++i)
      c.anchors.push_back(Vec4<R>(Vec3<R>(model.initial[i]), model.pinned[i] ? R(1) : R(0)));
  }
  // Where the colliders are at t = 0, at rest: set_substep_time takes over from the first substep.
  for (size_t k = 0; k < tl.spheres.size(); ++k)
    if (tl.spheres[k]) c.spheres[k].origin = Vec3<R>(interpolate(*tl.spheres[k], 0.0));
  for (size_t k = 0; k < tl.planes.size(); ++k)
    if (tl.planes[k]) c.planes[k].point = Vec3<R>(interpolate(*tl.planes[k], 0.0));
}

}  // namespace

template <class R> void set_substep_time(Constants<R>& c, double t) {
  const Timeline& tl = c.timeline;
  const double t1 = t + tl.dt;
  for (size_t k = 0; k < tl.spheres.size(); ++k)
    if (tl.spheres[k]) {
      const glm::dvec3 at = interpolate(*tl.spheres[k], t1);
      c.spheres[k].origin = Vec3<R>(at);
      c.spheres[k].motion = Vec3<R>(at - interpolate(*tl.spheres[k], t));  // rounded once, from double
    }
  for (size_t k = 0; k < tl.planes.size(); ++k)
    if (tl.planes[k]) {
      const glm::dvec3 at = interpolate(*tl.planes[k], t1);
      c.planes[k].point = Vec3<R>(at);
      c.planes[k].motion = Vec3<R>(at - interpolate(*tl.planes[k], t));
    }
  if (tl.pins) c.pin_offset = Vec3<R>(interpolate(*tl.pins, t1));
  if (tl.gust_period > 0) c.wind.gust_phase = R(gust_phase(t, tl.gust_period));
}

template <class R> Constants<R> make_constants(const Scene& scene, const ClothModel& model) {
  const ClothParams& cp = scene.cloth;
  const SimulationParams& sp = scene.simulation;
  Constants<R> c{};
  const double dt = scene.dt();
  // Derived values are formed in double and rounded once, identically for the GPU upload.
  c.gravity = Vec3<R>(sp.gravity);
  c.mass = R(particle_mass(cp));  // from the scene, so a live density edit takes effect
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
  make_wind(scene, c);
  make_timeline(scene, model, c);
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

// The parabolic stand-in for sin(2 pi phase) of the gusts: + - * and floor only, which both
// backends round alike (a shader's sin does not match std::sin); within 0.056 of the sine.
template <class R> R gust_wave(R phase) {
  const R w = phase - std::floor(phase);
  const R h = w < R(0.5) ? w : w - R(0.5);
  const R bump = R(16) * h * (R(0.5) - h);
  return w < R(0.5) ? bump : -bump;
}

// The share of one corner in the aerodynamic force on triangle (a, b, c), from its corners'
// positions and displacements (docs/model.md, "Wind"; wind.glsl is the twin).
template <class R>
Vec3<R> triangle_wind_share(const WindC<R>& w, const Vec3<R>& pa, const Vec3<R>& pb, const Vec3<R>& pc,
                            const Vec3<R>& da, const Vec3<R>& db, const Vec3<R>& dc) {
  const Vec3<R> u = pb - pa, v = pc - pa;
  const Vec3<R> twice_area_n(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
  const R len = length3(twice_area_n);
  if (!(len > R(0))) return Vec3<R>(0);  // a degenerate triangle catches no air
  const Vec3<R> n = twice_area_n * (R(1) / len);
  Vec3<R> air = w.velocity;
  if (w.gusts) {
    const R phase = w.gust_phase - dot3((pa + pb) + pc, w.direction) * w.gust_inv_length3;
    air = w.velocity + w.gust_velocity * gust_wave(phase);
  }
  const Vec3<R> rel = ((da + db) + dc) * w.inv_3dt - air;  // the triangle's velocity relative to the air
  const R speed = length3(rel);
  if (!(speed > R(0))) return Vec3<R>(0);
  const R normal_speed = dot3(rel, n);
  // Drag -1/2 rho C_d A |v| (v.n) n; lift -1/2 rho C_l A (v.n) (|v| n - (v.n)/|v| v), where
  // |v| n - (v.n)/|v| v is |v| times the part of n across v.
  const Vec3<R> drag = n * (w.drag * len * speed * normal_speed);
  const Vec3<R> across = n * speed - rel * (normal_speed * (R(1) / speed));
  return drag + across * (w.lift * len * normal_speed);
}

// Calls visit(t) for each of the up to six triangles (DESIGN.md §1) that have (x, y) as a
// corner, in a fixed order: the cells (x-1..x, y-1..y), each split into (A, C, B) and (B, C, D).
// compute_normals and compute_wind_forces gather over them, as their shaders do.
template <class Visit> void for_each_triangle_around(const ClothModel& m, int x, int y, Visit&& visit) {
  const int self = m.index(x, y);
  for (int cy = y - 1; cy <= y; ++cy)
    for (int cx = x - 1; cx <= x; ++cx) {
      if (cx < 0 || cy < 0 || cx + 1 >= m.nw || cy + 1 >= m.nh) continue;
      const int a = m.index(cx, cy), b = m.index(cx + 1, cy), cc = m.index(cx, cy + 1), dd = m.index(cx + 1, cy + 1);
      const int tris[2][3] = {{a, cc, b}, {b, cc, dd}};
      for (auto& t : tris)
        if (t[0] == self || t[1] == self || t[2] == self) visit(t);
    }
}

template <class R> void compute_wind_forces(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  s.wind.resize(s.pos.size());
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x) {
      const int self = m.index(x, y);
      Vec3<R> f(0);
      for_each_triangle_around(m, x, y, [&](const int (&t)[3]) {
        f += triangle_wind_share(c.wind, Vec3<R>(s.pos[t[0]]), Vec3<R>(s.pos[t[1]]), Vec3<R>(s.pos[t[2]]),
                                 Vec3<R>(s.disp[t[0]]), Vec3<R>(s.disp[t[1]]), Vec3<R>(s.disp[t[2]]));
      });
      s.wind[self] = Vec4<R>(f, R(0));
    }
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
      if (c.wind.enabled) f += Vec3<R>(s.wind[i]);  // after the springs, as advance.comp adds it
      s.force[i] = Vec4<R>(f, R(0));
    }
}

// A pinned mass keeps its position, or with pinned_motion goes to its anchor + the offset at
// the substep's end, and its displacement is that move (its velocity, for the springs'
// constraints, friction and the wind). The GLSL twin is move_pinned in pinned_motion.glsl.
template <class R> void move_pinned(const Constants<R>& c, size_t i, State<R>& s) {
  if (!c.moving_pins() || c.anchors[i].w == R(0)) return;
  const Vec3<R> next = Vec3<R>(c.anchors[i]) + c.pin_offset;
  s.disp[i] = Vec4<R>(next - Vec3<R>(s.pos[i]), R(0));
  s.pos[i] = Vec4<R>(next, s.pos[i].w);
}

template <class R> void integrate(const Constants<R>& c, State<R>& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const R w = s.pos[i].w;
    if (w == R(0)) {
      move_pinned(c, i, s);
      continue;
    }
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
  // Where pin k is at the end of this substep; a moving one from its anchor (as on the GPU,
  // where predict writes the pins while it reads them for the tethers).
  auto pin_position = [&](int k) {
    if (c.moving_pins() && c.anchors[k].w != R(0)) return Vec3<R>(Vec3<R>(c.anchors[k]) + c.pin_offset);
    return Vec3<R>(s.pos[k]);
  };
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const R w = s.pos[i].w;
    if (w == R(0)) {
      move_pinned(c, i, s);
      continue;
    }
    Vec3<R> acc = c.gravity;
    if (c.wind.enabled) acc = acc + Vec3<R>(s.wind[i]) * w;  // compute_wind_forces ran before
    Vec3<R> d = Vec3<R>(s.disp[i]) * c.keep_velocity + acc * c.dt2;
    Vec3<R> x = Vec3<R>(s.pos[i]) + d;
    if (const int pin = m.tether_pin[i]; pin >= 0) {
      const Vec3<R> e = x - pin_position(pin);
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
      // A correction must not push a mass into a collider or through a plane, where the
      // collision test of the next substep could no longer see it (docs/model.md).
      if (c.has_colliders()) {
        if (wi != R(0)) collide_particle(c, xi, di, false);
        if (wj != R(0)) collide_particle(c, xj, dj, false);
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
      for_each_triangle_around(m, x, y, [&](const int (&t)[3]) {
        const Vec3<R> p0(s.pos[t[0]]), p1(s.pos[t[1]]), p2(s.pos[t[2]]);
        const Vec3<R> u = p1 - p0, v = p2 - p0;
        // Unnormalised cross product: its length is twice the area, so this is area-weighted.
        sum += Vec3<R>(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
      });
      const R len = length3(sum);
      s.normal[m.index(x, y)] = len > R(0) ? Vec4<R>(sum * (R(1) / len), R(0)) : Vec4<R>(0, 1, 0, 0);
    }
}

#define CLOTHSIM_INSTANTIATE(R)                                                                         \
  template Constants<R> make_constants<R>(const Scene&, const ClothModel&);                           \
  template State<R> initial_state<R>(const ClothModel&);                                              \
  template void set_substep_time<R>(Constants<R>&, double);                                           \
  template void compute_wind_forces<R>(const ClothModel&, const Constants<R>&, State<R>&);            \
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

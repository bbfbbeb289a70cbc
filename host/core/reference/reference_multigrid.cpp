// The multigrid solver's passes (docs/model.md, "One substep (fabric solver)"), each the CPU
// twin of the compute shader of the same name. A substep solves implicit Euler,
//   minimise  sum_i m_i / (2 dt^2) |x_i - y_i|^2 + sum_s k_s / 2 (|x_j - x_i| - L_s)^2
// from the prediction y: one linear coarse-grid correction (a V-cycle over the hierarchy of
// hierarchy.hpp) carries tension across the whole cloth at once, then one nonlinear Gauss-Seidel
// sweep by vertex (a Newton step per mass on its 3x3 block) settles what is left locally. Both
// solve the same energy, so a rest state of the step is the static equilibrium of the springs.
#include "reference/reference.hpp"
#include "reference/reference_detail.hpp"
#include "reference/reference_material.hpp"
#include "reference/reference_skinning.hpp"
#include "../../../compute/shared/collisions.glsl"
#include "../../../compute/shared/integration.glsl"
#include "../../../compute/shared/springs.glsl"

#include <algorithm>

namespace clothsim {

namespace {

// A spring's Newton terms and the 3x3 block's solve, written once for both backends.
template <class R> using Sym3 = shared::Sym3<R>;
using shared::add_spring_hessian;
using shared::solve3;
using shared::spring_terms;

template <class R> void ensure_sized(const ClothModel& m, const Hierarchy& h, State<R>& s) {
  const size_t n = size_t(m.count()), coarse = h.coarse_count();
  // (predict sized and wrote the offsets already.)
  if (s.offset.size() != n) s.offset.assign(n, Vec4<R>(0));
  if (s.residual.size() != n + coarse) s.residual.assign(n + coarse, Vec4<R>(0));
  if (s.coarse_corr.size() != coarse) {
    s.coarse_rhs.assign(coarse, Vec4<R>(0));
    s.coarse_corr.assign(coarse, Vec4<R>(0));
  }
}

// b - A e at coarse vertex g, and A's diagonal block there (the linear coarse problem:
// A = M / dt^2 + the coarse springs' Hessians at the current positions).
template <class R>
Vec3<R> coarse_residual(const Hierarchy& h, const Constants<R>& c, const State<R>& s, uint32_t g, Sym3<R>& diag) {
  const Vec4<R> b = s.coarse_rhs[g];
  const R inertia = b.w * c.inv_dt2;
  const Vec3<R> e(s.coarse_corr[g]);
  const Vec3<R> p(s.pos[h.particle[g]]);
  Vec3<R> r = Vec3<R>(b) - e * inertia;
  diag = shared::sym3_diagonal(inertia);
  for (uint32_t k = h.spring_start[g]; k < h.spring_start[g + 1]; ++k) {
    const uint32_t o = h.spring_other[k];
    Vec3<R> n;
    R len, sa, sd;
    if (!spring_terms(p, Vec3<R>(s.pos[h.particle[o]]), R(h.spring_rest[k]), R(h.spring_k[k]), n, len, sa, sd)) continue;
    const Vec3<R> v = e - Vec3<R>(s.coarse_corr[o]);
    r = r - shared::spring_hessian_times(n, sa, sd, v);
    add_spring_hessian(diag, n, sa, sd);
  }
  return r;
}

// A mass at x within kContactReach of a collider's surface (inside a sphere or within the
// reach of it, behind a plane's front or within the reach in front, within a mesh's thickness
// plus the reach). The collider holds it with whatever force it takes, a force the coarse
// problem does not know: such a mass neither gives its residual to the coarse levels nor takes
// their correction, and the sweep alone moves it (docs/model.md). The GLSL twin is
// touches_colliders in compute/multigrid.glsl.
template <class R> bool touches_colliders(const Constants<R>& c, const Vec3<R>& x, uint32_t* slots) {
  const R reach = R(kContactReach);
  for (const SphereColliderT<R>& sp : c.control.spheres)
    if (shared::near_sphere(x, Vec3<R>(sp.origin_radius), sp.origin_radius.w, reach)) return true;
  for (const PlaneColliderT<R>& pl : c.control.planes)
    if (shared::near_plane(x, Vec3<R>(pl.point), Vec3<R>(pl.normal), pl.point.w, reach)) return true;  // w: front
  MeshColliderT<R> frame;  // a skinned collider's, at x (no move: d = 0)
  for (const MeshColliderT<R>& m : c.control.meshes) {
    R phi;
    Vec3<R> grad;
    const MeshColliderT<R>* at = mesh_at(c, m, x, Vec3<R>(0), frame, slots, false);
    if (at && sample_mesh_at(*at, c.sdf->data(), x, phi, grad) && phi < m.material.y + reach) return true;  // y: thickness
  }
  return false;
}

// Coarse vertex g in a fold: one of its coarse springs is shorter than c.folded_chord of its rest
// length, the cloth between its ends buckled or folded. A coarse spring's chord says nothing of
// the cloth there, and the local sweep does well where the cloth is slack: such a vertex is
// fixed in the coarse problem, which carries tension where the cloth is taut.
template <class R> bool folded(const Hierarchy& h, const Constants<R>& c, const State<R>& s, uint32_t g) {
  const uint32_t i = h.particle[g];
  const Vec3<R> p(s.pos[i]);
  const R chord = shared::folded_chord_at(c.start_ks[i] * s.pos[i].w, c);
  for (uint32_t k = h.spring_start[g]; k < h.spring_start[g + 1]; ++k)
    if (length3(Vec3<R>(s.pos[h.particle[h.spring_other[k]]]) - p) < chord * R(h.spring_rest[k])) return true;
  return false;
}

}  // namespace

template <class R> void compute_residuals(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  ensure_sized(m, *c.hierarchy, s);
  for (uint32_t i = 0; i < uint32_t(m.count()); ++i) {
    if (s.pos[i].w == R(0)) {
      s.residual[i] = Vec4<R>(0);
      continue;
    }
    // -m/dt^2 (x - y) + the springs' force at the start x = y + offset, the prediction less
    // the external forces' share: the classic force, gravity and the wind included.
    const Vec3<R> off(s.offset[i]);
    const Vec3<R> xi = Vec3<R>(s.pos[i]) + off;
    if (c.has_colliders() && touches_colliders(c, xi, skin_slots(c, s, i))) {
      s.residual[i] = Vec4<R>(Vec3<R>(0), c.mass[i]);
      continue;
    }
    Vec3<R> f = off * -(c.mass[i] * c.inv_dt2);
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
      const Spring& sp = m.springs[m.gather[g]];
      if (!c.enabled(sp)) continue;
      const uint32_t j = sp.i == i ? sp.j : sp.i;
      const Vec3<R> e = (Vec3<R>(s.pos[j]) + Vec3<R>(s.offset[j])) - xi;
      f = shared::add_spring_force(f, e, c.rest_of(sp), c.stiffness_of(m, sp));
    }
    Sym3<R> unused = shared::sym3_diagonal(R(0));
    f = add_material_terms(m, c, i, xi, [&](uint32_t j) { return Vec3<R>(s.pos[j]) + Vec3<R>(s.offset[j]); }, f, unused, false);
    if (c.has_attachments() && c.attach[i].w != R(0))
      f = shared::add_anchor_pull(f, xi, Vec3<R>(c.attach[i]), c.attached_origin(i), c.attach[i].w);
    // The coarse problem weighs each mass with its hinges' block as inertia (hinge_inertia).
    const R weight = c.mass[i] + c.dt2 * hinge_block(m, i, R(0));
    s.residual[i] = Vec4<R>(f, weight);
  }
}

template <class R> void restrict_residuals(const Constants<R>& c, int level, State<R>& s) {
  const Hierarchy& h = *c.hierarchy;
  const HierarchyLevel& l = h.levels[size_t(level)];
  for (uint32_t g = l.first; g < l.first + l.count; ++g) {
    s.coarse_corr[g] = Vec4<R>(0);
    const uint32_t p = h.particle[g];
    if (s.pos[p].w == R(0) || (c.has_colliders() && touches_colliders(c, Vec3<R>(s.pos[p]) + Vec3<R>(s.offset[p]), skin_slots(c, s, p))) ||
        folded(h, c, s, g)) {
      // Pinned, held, held by a collider or in a fold: fixed in the coarse problem (w -1 says so).
      s.coarse_rhs[g] = Vec4<R>(0, 0, 0, -1);
      s.residual[s.pos.size() + g] = Vec4<R>(0);
      continue;
    }
    Vec4<R> b(0);
    for (uint32_t k = h.child_start[g]; k < h.child_start[g + 1]; ++k) b += s.residual[h.child[k]] * R(h.child_weight[k]);
    s.coarse_rhs[g] = b;  // xyz: the force; w: the mass the vertex stands for
    // With the correction at zero the level's residual is b itself: the next level restricts it.
    s.residual[s.pos.size() + g] = b;
  }
}

template <class R> void smooth_corrections(const Constants<R>& c, int level, int colour, State<R>& s) {
  const Hierarchy& h = *c.hierarchy;
  const HierarchyLevel& l = h.levels[size_t(level)];
  for (uint32_t k = l.colour_start[size_t(colour)]; k < l.colour_start[size_t(colour) + 1]; ++k) {
    const uint32_t g = h.order[k];
    if (s.coarse_rhs[g].w < R(0)) continue;  // a fixed vertex does not move (restrict_residuals)
    Sym3<R> diag;
    const Vec3<R> r = coarse_residual(h, c, s, g, diag);
    Vec3<R> step;
    if (solve3(diag, r, step)) s.coarse_corr[g] = Vec4<R>(Vec3<R>(s.coarse_corr[g]) + step, R(0));
  }
}

template <class R> void prolong_corrections(const Constants<R>& c, int level, State<R>& s) {
  const Hierarchy& h = *c.hierarchy;
  const HierarchyLevel& l = h.levels[size_t(level)];
  for (uint32_t g = l.first; g < l.first + l.count; ++g) {
    if (s.coarse_rhs[g].w < R(0)) continue;
    Vec3<R> e(0);
    for (uint32_t k = h.parent_start[g]; k < h.parent_start[g + 1]; ++k)
      e += Vec3<R>(s.coarse_corr[h.parent[k]]) * R(h.parent_weight[k]);
    s.coarse_corr[g] = Vec4<R>(Vec3<R>(s.coarse_corr[g]) + e, R(0));
  }
}

template <class R> void prolong_to_cloth(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  const Hierarchy& h = *c.hierarchy;
  for (uint32_t i = 0; i < uint32_t(m.count()); ++i) {
    // From the prediction to the start (the offset predict left) plus the correction.
    const Vec3<R> off(s.offset[i]);
    Vec3<R> e(0);
    if (s.pos[i].w != R(0) && !(c.has_colliders() && touches_colliders(c, Vec3<R>(s.pos[i]) + off, skin_slots(c, s, i))))
      for (uint32_t k = h.fine_parent_start[i]; k < h.fine_parent_start[i + 1]; ++k)
        e += Vec3<R>(s.coarse_corr[h.fine_parent[k]]) * R(h.fine_parent_weight[k]);
    s.pos[i] = Vec4<R>((Vec3<R>(s.pos[i]) + off) + e, s.pos[i].w);
    s.disp[i] = Vec4<R>((Vec3<R>(s.disp[i]) + off) + e, R(0));
    s.offset[i] = Vec4<R>(off + e, R(0));  // x - y, the inertia term of the sweep
  }
}

template <class R> void relax_vertices(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s) {
  const Hierarchy& h = *c.hierarchy;
  for (uint32_t k = h.fine_colour_start[size_t(colour)]; k < h.fine_colour_start[size_t(colour) + 1]; ++k) {
    const uint32_t i = h.fine_order[k];
    const R wi = s.pos[i].w;
    if (wi == R(0)) continue;
    Vec3<R> x(s.pos[i]), d(s.disp[i]), off(s.offset[i]);
    const R inertia = c.mass[i] * c.inv_dt2;
    // Newton on this mass's block: f = -m/dt^2 (x - y) + the springs' forces, H = m/dt^2 I + their Hessians.
    Vec3<R> f = off * -inertia;
    Sym3<R> hess = shared::sym3_diagonal(inertia);
    // The least room any spring has left below 99 % of its limit, for skipping the limit's loop
    // (as the shader does: below).
    R headroom = R(3.0e38);
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
      const Spring& sp = m.springs[m.gather[g]];
      if (!c.enabled(sp)) continue;
      const uint32_t j = sp.i == i ? sp.j : sp.i;
      Vec3<R> n;
      R len, sa, sd;
      const R k_s = c.stiffness_of(m, sp), rest = c.rest_of(sp);
      const bool taut = spring_terms(x, Vec3<R>(s.pos[j]), rest, k_s, n, len, sa, sd);
      // A seam's limit is enforce_stretch_limit's (its weld): this loop moves one end at a time.
      if (sp.type != SpringType::Seam) headroom = std::min(headroom, R(0.99) * c.stretch_limit * rest - len);
      if (!taut) continue;
      f = shared::add_spring_pull(f, n, len, rest, k_s);
      add_spring_hessian(hess, n, sa, sd);
    }
    f = add_material_terms(m, c, i, x, [&](uint32_t j) { return Vec3<R>(s.pos[j]); }, f, hess, true);
    // An attachment: its pull and its block k I (docs/model.md, "Attachments").
    if (c.has_attachments() && c.attach[i].w != R(0)) {
      f = shared::add_anchor_pull(f, x, Vec3<R>(c.attach[i]), c.attached_origin(i), c.attach[i].w);
      add_spring_hessian(hess, Vec3<R>(0), R(0), c.attach[i].w);
    }
    if (c.bounded_contact && c.sweep_friction)  // fabric's sweep (docs/model.md, "Self-contact in the sweep")
      add_self_contacts(c, s, i, x, x - d, f, hess);
    Vec3<R> step;
    if (solve3(hess, f, step)) {
      x = x + step;
      d = d + step;
      off = off + step;
    }
    // max_stretch as a hard limit: each spring still longer than (1 + max_stretch) rest pulls
    // this mass its share of the way back (Provot's projection, one end at a time). A spring
    // grows by at most |step| (no spring joins two masses of a colour), so where every spring
    // had more room than that, with a margin far above the rounding, the loop could change
    // nothing and is skipped, as relax_vertices.comp skips it: the same bits, a third less time.
    const bool may_limit = !(length3(step) + R(1.0e-6) * (length3(x) + R(1)) < headroom);
    for (uint32_t g = m.gather_start[i]; may_limit && g < m.gather_start[i + 1]; ++g) {
      const Spring& sp = m.springs[m.gather[g]];
      if (!c.enabled(sp) || sp.type == SpringType::Seam) continue;
      const uint32_t j = sp.i == i ? sp.j : sp.i;
      const R wj = s.pos[j].w;
      const Vec3<R> e = Vec3<R>(s.pos[j]) - x;
      const R len = length3(e);
      const R limit = c.stretch_limit * c.rest_of(sp);
      if (!(len > limit)) continue;
      const Vec3<R> corr = shared::one_end_stretch_pull(e, len, limit, wi, wj);
      x = x + corr;
      d = d + corr;
    }
    // A correction must not push a mass into a collider or through a plane (the sweep's push-out).
    // fabric: with Coulomb friction against colliders that did not move this substep, so the
    // sweep's own moves along a surface are held as the prediction's are (without it a drape
    // creeps off a sphere: 22 mm over frames 90-300); none against a moving one (takes_friction).
    if (c.has_colliders()) collide_particle(c, x, d, c.sweep_friction != 0u, skin_slots(c, s, i), /*search=*/false,
                                           /*still_only=*/true);
    s.pos[i] = Vec4<R>(x, wi);
    s.disp[i] = Vec4<R>(d, R(0));
    s.offset[i] = Vec4<R>(off, R(0));
  }
}

template <class R> void smooth_level(const Constants<R>& c, int level, int sweeps, State<R>& s) {
  const int colours = int(c.hierarchy->levels[size_t(level)].colour_start.size()) - 1;
  for (int it = 0; it < sweeps; ++it)
    for (int k = 0; k < colours; ++k) smooth_corrections(c, level, k, s);
}

template <class R> void solve_coarsest(const Constants<R>& c, State<R>& s) {
  smooth_level(c, int(c.hierarchy->levels.size()) - 1, kCoarsestSweeps, s);
}

int first_small_level(const Hierarchy& h) {
  int l = int(h.levels.size()) - 1;
  while (l > 0 && h.levels[size_t(l - 1)].count <= kSmallLevelVertices) --l;
  return std::max(l, 0);
}

template <class R> void cycle_small_levels(const Constants<R>& c, State<R>& s) {
  const int levels = int(c.hierarchy->levels.size()), small = first_small_level(*c.hierarchy);
  if (levels == 0) return;
  for (int l = small; l < levels; ++l) restrict_residuals(c, l, s);
  solve_coarsest(c, s);
  for (int l = levels - 2; l >= small; --l) {
    prolong_corrections(c, l, s);
    smooth_level(c, l, kLevelSweeps, s);
  }
}

template <class R> void cycle_levels(const Constants<R>& c, State<R>& s) {
  const int levels = int(c.hierarchy->levels.size()), small = first_small_level(*c.hierarchy);
  if (levels == 0) return;
  // Down: the force restricted level by level (no smoothing on the way down: the correction
  // is zero there, so each level's residual is its right-hand side); the small levels, the
  // coarsest solve and the way back up to the first small level in cycle_small_levels.
  for (int l = 0; l < small; ++l) restrict_residuals(c, l, s);
  cycle_small_levels(c, s);
  // Up: add each level's correction to the finer one, smooth it there.
  for (int l = small - 1; l >= 0; --l) {
    prolong_corrections(c, l, s);
    smooth_level(c, l, kLevelSweeps, s);
  }
}

template <class R> void solve_multigrid(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  compute_residuals(m, c, s);
  cycle_levels(c, s);
  prolong_to_cloth(m, c, s);
  for (int k = 0; k < c.hierarchy->fine_colours(); ++k) relax_vertices(m, c, k, s);
}

#define CLOTHSIM_INSTANTIATE(R) \
  template void compute_residuals<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void restrict_residuals<R>(const Constants<R>&, int, State<R>&); \
  template void smooth_corrections<R>(const Constants<R>&, int, int, State<R>&); \
  template void prolong_corrections<R>(const Constants<R>&, int, State<R>&); \
  template void prolong_to_cloth<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void relax_vertices<R>(const ClothModel&, const Constants<R>&, int, State<R>&); \
  template void smooth_level<R>(const Constants<R>&, int, int, State<R>&); \
  template void solve_coarsest<R>(const Constants<R>&, State<R>&); \
  template void cycle_small_levels<R>(const Constants<R>&, State<R>&); \
  template void cycle_levels<R>(const Constants<R>&, State<R>&); \
  template void solve_multigrid<R>(const ClothModel&, const Constants<R>&, State<R>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

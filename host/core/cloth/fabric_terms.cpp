// The membrane and bending terms of the cloths with a material (docs/materials.md, "How the
// model uses them"): per particle, the triangles around it, its row of the flat bending
// stencils' Q and the curved hinges it is part of, in the material's frame, so one gather per
// particle gives the fabric sweep its forces and Hessian.
#include <cmath>
#include <algorithm>
#include <map>

#include <glm/geometric.hpp>

#include "cloth/fabric_terms.hpp"

namespace clothsim {

void add_stencil(Stencils& out, const std::vector<uint32_t>& v, const std::vector<double>& w, double rest) {
  if (rest == 0) {
    for (size_t s = 0; s < v.size(); ++s)
      for (size_t q = 0; q < v.size(); ++q) out.rows[v[s]][v[q]] += w[s] * w[q];
    return;
  }
  for (size_t s = 0; s < v.size(); ++s) {
    HingeEntry h;
    h.rest = rest;
    h.k[0] = w[s];
    size_t o = 0;
    for (size_t q = 0; q < v.size(); ++q)
      if (q != s) {
        h.other[o] = v[q];
        h.k[o + 1] = w[q];
        ++o;
      }
    for (; o < 3; ++o) {
      h.other[o] = h.other[0];
      h.k[o + 1] = 0;
    }
    out.hinges[v[s]].push_back(h);
  }
}

namespace {

TriangleFrame frame_of(const ClothModel& m, const std::array<uint32_t, 3>& t) {
  TriangleFrame f;
  const glm::dvec3 p0 = m.initial[t[0]], e1 = m.initial[t[1]] - p0, e2 = m.initial[t[2]] - p0;
  const glm::dvec3 c = glm::cross(e1, e2);
  f.area = 0.5 * glm::length(c);
  if (!(f.area > 0)) return f;
  const glm::dvec3 n = c / (2 * f.area);
  const glm::dvec2 d1 = m.uv[t[1]] - m.uv[t[0]], d2 = m.uv[t[2]] - m.uv[t[0]];
  const double det = d1.x * d2.y - d2.x * d1.y;
  glm::dvec3 u = e1;
  if (std::abs(det) > 1e-12) u = (e1 * d2.y - e2 * d1.y) / det;  // dp/du
  u -= n * glm::dot(n, u);
  if (!(glm::length(u) > 1e-12 * glm::length(e1))) u = e1;
  f.u = glm::normalize(u);
  f.v = glm::cross(n, f.u);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 r = m.initial[t[size_t(k)]] - p0;
    f.q[k] = {glm::dot(r, f.u), glm::dot(r, f.v)};
  }
  return f;
}

double cot(const glm::dvec3& a, const glm::dvec3& b) {
  const double s = glm::length(glm::cross(a, b));
  return s > 0 ? glm::dot(a, b) / s : 0.0;
}

// A grid's bending: an orthotropic plate with no Poisson coupling, energy per area
// (B_warp k_xx^2 + B_weft k_yy^2 + 2 sqrt(B_warp B_weft) k_xy^2) / 2, its curvatures the
// second differences of the positions (the curvature vector of an isometric bend): k_xx at
// every particle with a neighbour either side along x (over its own area), k_yy likewise,
// k_xy on every cell. Isotropic where B_warp = B_weft (a bend at any angle to the grid costs
// the same), and flat at rest (the jitter of a vertical grid is a start, not a shape).
void add_grid_stencils(const ClothModel& m, const ClothPart& part, const ClothParams& p, Stencils& stencils) {
  const MaterialParams& mat = *p.material;
  const int nw = part.nw, nh = part.nh;
  const double hx = p.width / (nw - 1), hy = p.height / (nh - 1);
  auto at = [&](int x, int y) { return part.first + uint32_t(y * nw + x); };
  auto area = [&](int x, int y) {  // the particle's share of the cloth
    return hx * hy * ((x == 0 || x == nw - 1) ? 0.5 : 1.0) * ((y == 0 || y == nh - 1) ? 0.5 : 1.0);
  };
  // A stencil centred on a pinned particle with one neighbour pinned and the other free
  // measures the bend at a clamped edge: there the curvature of the free side continues into
  // the clamp as its mirror image (the slope is held), so the stencil stands for twice its
  // one-sided difference's energy. Without it the strip bends as if clamped half a spacing
  // inside the clamp: a cantilever 20 % too soft at ten particles along it (docs/materials.md).
  auto clamp = [&](uint32_t c, uint32_t a, uint32_t b) {
    return m.pinned[c] && (m.pinned[a] != m.pinned[b]) ? 2.0 : 1.0;
  };
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) {
      if (x > 0 && x + 1 < nw) {
        const double s =
            std::sqrt(mat.bending[0] * area(x, y) * clamp(at(x, y), at(x - 1, y), at(x + 1, y))) / (hx * hx);
        add_stencil(stencils, {at(x, y), at(x - 1, y), at(x + 1, y)}, {-2 * s, s, s}, 0);
      }
      if (y > 0 && y + 1 < nh) {
        const double s =
            std::sqrt(mat.bending[1] * area(x, y) * clamp(at(x, y), at(x, y - 1), at(x, y + 1))) / (hy * hy);
        add_stencil(stencils, {at(x, y), at(x, y - 1), at(x, y + 1)}, {-2 * s, s, s}, 0);
      }
      if (x + 1 < nw && y + 1 < nh) {
        const double s = std::sqrt(2 * std::sqrt(mat.bending[0] * mat.bending[1]) * hx * hy) / (hx * hy);
        add_stencil(stencils, {at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)}, {s, -s, -s, s}, 0);
      }
    }
}

// Whether a mesh's rest shape is flat: every triangle's normal along the first's, either way
// round (a flat panel, which bends as a plate, whatever its winding), not a curved shell (which
// keeps its rest curvature through hinges).
bool flat(const std::vector<TriangleFrame>& frames) {
  glm::dvec3 n0(0.0);
  for (const TriangleFrame& f : frames) {
    if (!(f.area > 0)) continue;
    const glm::dvec3 n = glm::cross(f.u, f.v);
    if (n0 == glm::dvec3(0.0)) n0 = n;
    if (!(std::abs(glm::dot(n, n0)) > 1 - 1e-9)) return false;
  }
  return true;
}

}  // namespace

void add_fabric_terms(const Scene& scene, ClothModel& m) {
  const auto cloths = scene.cloths();
  bool any = false;
  for (const ClothParams* c : cloths) any = any || c->material.has_value();
  if (!any) return;
  const size_t n = size_t(m.count());
  std::vector<std::vector<MembraneEntry>> membrane(n);
  Stencils stencils;
  stencils.rows.resize(n);
  stencils.hinges.resize(n);
  std::vector<uint8_t> has_row(n, 0);
  for (size_t k = 0; k < m.parts.size(); ++k) {
    if (!cloths[k]->material) continue;
    const MaterialParams& mat = *cloths[k]->material;
    const ClothPart& part = m.parts[k];
    for (uint32_t i = part.first; i < part.first + part.count; ++i) has_row[i] = 1;
    std::vector<TriangleFrame> frames;
    for (uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      const auto& tri = m.triangles[t];
      frames.push_back(frame_of(m, tri));
      const TriangleFrame& f = frames.back();
      if (!(f.area > 0)) continue;  // a degenerate triangle has no membrane
      for (int c = 0; c < 3; ++c) {
        const int a = (c + 1) % 3, b = (c + 2) % 3;
        const glm::dvec2 da = f.q[a] - f.q[c], db = f.q[b] - f.q[c];
        const double det = da.x * db.y - db.x * da.y;
        MembraneEntry e;
        e.a = tri[size_t(a)];
        e.b = tri[size_t(b)];
        e.area = f.area;
        // [da db]^-1, row-major.
        e.dminv = {db.y / det, -db.x / det, -da.y / det, da.x / det};
        membrane[tri[size_t(c)]].push_back(e);
      }
    }
    if (part.nw > 0) {
      add_grid_stencils(m, part, *cloths[k], stencils);
      continue;
    }
    if (flat(frames)) {
      add_mesh_plate_stencils(m, part, mat, frames, stencils);
      continue;
    }
    // A curved mesh's bending: the quadratic model's hinges (Bergou et al. 2006) on its interior edges,
    // in order of discovery: the two triangles on each and their opposite corners.
    std::map<std::pair<uint32_t, uint32_t>, size_t> edge_index;
    struct Edge {
      uint32_t x0, x1, t0, opp0, t1 = UINT32_MAX, opp1 = 0;
    };
    std::vector<Edge> edges;
    for (uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      if (!(frames[t - part.first_triangle].area > 0)) continue;
      const auto& tri = m.triangles[t];
      for (int c = 0; c < 3; ++c) {
        const uint32_t p = tri[size_t(c)], q = tri[size_t((c + 1) % 3)], o = tri[size_t((c + 2) % 3)];
        const auto key = std::minmax(p, q);
        auto [it, fresh] = edge_index.try_emplace({key.first, key.second}, edges.size());
        if (fresh) edges.push_back({p, q, t, o});
        else if (edges[it->second].t1 == UINT32_MAX) {
          edges[it->second].t1 = t;
          edges[it->second].opp1 = o;
        } else edges[it->second].t1 = UINT32_MAX - 1;  // a third triangle: no hinge (non-manifold)
      }
    }
    // How many hinges each triangle has: its area is shared among them, so the cloth's edge
    // strips are not under-weighted (docs/materials.md).
    std::vector<int> hinge_count(part.triangle_count, 0);
    auto is_hinge = [&](const Edge& e) { return e.t1 < UINT32_MAX - 1; };
    for (const Edge& e : edges)
      if (is_hinge(e)) {
        ++hinge_count[e.t0 - part.first_triangle];
        ++hinge_count[e.t1 - part.first_triangle];
      }
    for (const Edge& e : edges) {
      if (!is_hinge(e)) continue;
      const std::array<uint32_t, 4> v = {e.x0, e.x1, e.opp0, e.opp1};
      const glm::dvec3 x0 = m.initial[v[0]], e0 = m.initial[v[1]] - x0, e1 = m.initial[v[2]] - x0,
                       e2 = m.initial[v[3]] - x0, e3 = m.initial[v[2]] - m.initial[v[1]],
                       e4 = m.initial[v[3]] - m.initial[v[1]];
      const double c01 = cot(e0, e1), c02 = cot(e0, e2), c03 = cot(-e0, e3), c04 = cot(-e0, e4);
      const TriangleFrame& f0 = frames[e.t0 - part.first_triangle];
      const TriangleFrame& f1 = frames[e.t1 - part.first_triangle];
      const double a0 = f0.area, a1 = f1.area;
      const double share = a0 / hinge_count[e.t0 - part.first_triangle] + a1 / hinge_count[e.t1 - part.first_triangle];
      // The hinge measures the curvature across its edge: warp rigidity for an edge along the
      // weft, weft rigidity for one along the warp, the mix in between.
      const glm::dvec3 along = glm::normalize(e0);
      const double eu = glm::dot(along, f0.u), ev = glm::dot(along, f0.v);
      const double rigidity = mat.bending[0] * ev * ev + mat.bending[1] * eu * eu;
      const double scale = std::sqrt(rigidity * 3.0 * share / ((a0 + a1) * (a0 + a1)));
      const std::array<double, 4> w = {(c03 + c04) * scale, (c01 + c02) * scale, -(c01 + c03) * scale,
                                        -(c02 + c04) * scale};
      // The rest shape's curvature vector, relative to the hinge's first particle; a flat rest
      // gives the rounding's 1e-16 of the terms, taken as exactly flat: a rest of that size
      // would make the nearly flat hinge's block k^2 n n^T along a direction of rounding noise
      // (spring_terms with len < rest) instead of k^2 I, and the sweep's step overshoot.
      glm::dvec3 rest(0.0);
      double terms = 0;
      for (int q = 1; q < 4; ++q) {
        rest += (m.initial[v[size_t(q)]] - x0) * w[size_t(q)];
        terms += std::abs(w[size_t(q)]) * glm::length(m.initial[v[size_t(q)]] - x0);
      }
      const double curvature = glm::length(rest) > 1e-9 * terms ? glm::length(rest) : 0.0;
      add_stencil(stencils, {v.begin(), v.end()}, {w.begin(), w.end()}, curvature);
    }
  }
  m.membrane_start.assign(1, 0);
  m.bend_start.assign(1, 0);
  m.hinge_start.assign(1, 0);
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    m.membrane.insert(m.membrane.end(), membrane[i].begin(), membrane[i].end());
    m.hinges.insert(m.hinges.end(), stencils.hinges[i].begin(), stencils.hinges[i].end());
    if (has_row[i]) {  // Q_ii first, then the others ascending, padded to pairs (a texel each)
      auto& row = stencils.rows[i];
      m.bend.push_back({i, row.count(i) ? row[i] : 0.0});
      for (const auto& [j, q] : row)
        if (j != i) m.bend.push_back({j, q});
      if ((m.bend.size() - m.bend_start.back()) % 2) m.bend.push_back({i, 0.0});
    }
    m.membrane_start.push_back(uint32_t(m.membrane.size()));
    m.bend_start.push_back(uint32_t(m.bend.size()));
    m.hinge_start.push_back(uint32_t(m.hinges.size()));
  }
  // A material particle's springs add no force (the scene may not turn them on beside a
  // material; its structural ones serve max_stretch's passes alone, which go by colour): its
  // gather keeps only its seams, so no sweep walks the rest to skip them.
  std::vector<uint32_t> start(1, 0), gather;
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g)
      if (!has_row[i] || m.springs[m.gather[g]].type == SpringType::Seam) gather.push_back(m.gather[g]);
    start.push_back(uint32_t(gather.size()));
  }
  m.gather_start = std::move(start);
  m.gather = std::move(gather);
}

}  // namespace clothsim

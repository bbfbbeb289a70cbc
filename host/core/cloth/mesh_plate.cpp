// A flat mesh's bending as an orthotropic plate (docs/materials.md, "How the model uses them"):
// the grid's energy per area (B_warp k_uu^2 + B_weft k_vv^2 + 2 sqrt(B_warp B_weft) k_uv^2) / 2
// with its curvatures the second derivatives, in the material's frame, of a quadratic fitted by
// least squares to each inner vertex and its ring. A quadratic's derivatives are linear in the
// positions, so each is a stencil with a flat rest, summed into Q's rows. Unlike the hinges of
// the quadratic model (one curvature per edge, across it), which price a bend by how the mesh's
// edges happen to lie (a cylinder costs 1.13 to 1.8 times B k^2 / 2 on the meshes measured), the
// fit sees every direction at every vertex: a bend costs the same on any triangulation.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include "cloth/fabric_terms.hpp"

namespace clothsim {
namespace {

// The least-squares fit of x_j - x_c = g_u du + g_v dv + (h_uu du^2 + 2 h_uv du dv + h_vv dv^2) / 2
// over the neighbours' rest offsets (du, dv): the rows of its pseudo-inverse for h_uu, h_uv and
// h_vv (each x_j's weight). False where the neighbours do not determine a quadratic (fewer than
// five, or all near one conic).
bool fit_second_derivatives(const std::vector<glm::dvec2>& d, Eigen::Matrix<double, 3, Eigen::Dynamic>& rows) {
  const Eigen::Index n = Eigen::Index(d.size());
  if (n < 5) return false;
  double scale = 0;  // the columns in units of the mean distance, for the conditioning test
  for (const glm::dvec2& p : d) scale += glm::length(p);
  scale = double(n) / scale;
  Eigen::MatrixXd a(n, 5);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double u = d[size_t(j)].x * scale, v = d[size_t(j)].y * scale;
    a.row(j) << u, v, 0.5 * u * u, u * v, 0.5 * v * v;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto& s = svd.singularValues();
  if (!(s(4) > 1e-3 * s(0))) return false;
  const Eigen::MatrixXd pinv = svd.matrixV() * s.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
  rows = pinv.bottomRows(3) * (scale * scale);  // back to metres: h scales as 1/length^2
  return true;
}

}  // namespace

void add_mesh_plate_stencils(const ClothModel& m, const ClothPart& part, const MaterialParams& mat,
                             const std::vector<TriangleFrame>& frames, Stencils& out) {
  // The ring of each vertex and its triangles; a vertex on an edge with one triangle (or more
  // than two) is on the boundary, where a ring is half a ring and fits no quadratic.
  std::map<uint32_t, std::set<uint32_t>> ring;
  std::map<uint32_t, std::vector<uint32_t>> around;
  std::map<std::pair<uint32_t, uint32_t>, int> edge_triangles;
  for (uint32_t t = 0; t < part.triangle_count; ++t) {
    if (!(frames[t].area > 0)) continue;
    const auto& tri = m.triangles[part.first_triangle + t];
    for (int c = 0; c < 3; ++c) {
      const uint32_t p = tri[size_t(c)], q = tri[size_t((c + 1) % 3)];
      ring[p].insert(q);
      ring[q].insert(p);
      around[p].push_back(t);
      ++edge_triangles[std::minmax(p, q)];
    }
  }
  std::set<uint32_t> boundary;
  for (const auto& [e, count] : edge_triangles)
    if (count != 2) boundary.insert({e.first, e.second});
  // Each triangle's area goes to its inner corners, so the boundary's strip is not lost.
  std::map<uint32_t, double> area;
  for (uint32_t t = 0; t < part.triangle_count; ++t) {
    if (!(frames[t].area > 0)) continue;
    const auto& tri = m.triangles[part.first_triangle + t];
    const auto inner = std::count_if(tri.begin(), tri.end(), [&](uint32_t v) { return !boundary.count(v); });
    for (uint32_t v : tri)
      if (inner > 0 && !boundary.count(v)) area[v] += frames[t].area / double(inner);
  }
  const double rigidity[3] = {mat.bending[0], 2 * std::sqrt(mat.bending[0] * mat.bending[1]), mat.bending[1]};
  for (const auto& [c, a] : area) {
    // The material's frame at c: its triangles' warp, averaged (one direction on a flat mesh
    // whose texture is affine), and the weft across it. Without texture coordinates each
    // triangle's warp is its first edge, and opposite edges can cancel: then the first
    // triangle's (the plate is isotropic where warp = weft).
    const TriangleFrame& first = frames[around[c][0]];
    const glm::dvec3 n = glm::cross(first.u, first.v);
    glm::dvec3 u(0.0);
    double total = 0;
    for (uint32_t t : around[c]) {
      u += frames[t].u * frames[t].area;
      total += frames[t].area;
    }
    u -= n * glm::dot(n, u);
    u = glm::length(u) > 0.1 * total ? glm::normalize(u) : first.u;
    const glm::dvec3 v = glm::cross(n, u);
    // The ring, or the ring and the ring's rings where the ring alone fits no quadratic.
    std::vector<uint32_t> members(ring[c].begin(), ring[c].end());
    std::vector<glm::dvec2> d;
    Eigen::Matrix<double, 3, Eigen::Dynamic> rows;
    for (int reach = 1; reach <= 2; ++reach) {
      if (reach == 2) {
        std::set<uint32_t> wider(members.begin(), members.end());
        for (uint32_t j : members) wider.insert(ring[j].begin(), ring[j].end());
        wider.erase(c);
        members.assign(wider.begin(), wider.end());
      }
      d.clear();
      for (uint32_t j : members) {
        const glm::dvec3 r = m.initial[j] - m.initial[c];
        d.push_back({glm::dot(r, u), glm::dot(r, v)});
      }
      if (fit_second_derivatives(d, rows)) break;
      rows.resize(3, 0);
    }
    if (rows.cols() == 0) continue;  // no quadratic even over two rings: a sliver of cloth
    std::vector<uint32_t> stencil = {c};
    stencil.insert(stencil.end(), members.begin(), members.end());
    // A pinned vertex with pinned and free vertices round it is on a clamped edge: as on a
    // grid (fabric_terms.cpp), the free side's bend continues into the clamp as its mirror
    // image, and the fit, which sees half of it, stands for twice its energy.
    const auto pinned = std::count_if(members.begin(), members.end(), [&](uint32_t j) { return m.pinned[j] != 0; });
    const double clamp = m.pinned[c] && pinned > 0 && pinned < std::ssize(members) ? 2.0 : 1.0;
    for (int k = 0; k < 3; ++k) {
      const double s = std::sqrt(rigidity[k] * a * clamp);
      std::vector<double> w = {-rows.row(k).sum() * s};
      for (Eigen::Index j = 0; j < rows.cols(); ++j) w.push_back(rows(k, j) * s);
      add_stencil(out, stencil, w, 0);
    }
  }
}

}  // namespace clothsim

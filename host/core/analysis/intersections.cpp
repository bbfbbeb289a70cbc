// Exact self-intersection count (intersections.hpp): Devillers-Guigue's triangle pair test on
// the exact orientation predicates (exact_predicates.cpp), and a uniform spatial hash of the
// triangles' bounding boxes.
#include "analysis/intersections.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "analysis/exact_predicates.hpp"

namespace clothsim {
namespace exact {

using detail::kEps;
using detail::kUncertain;
using detail::orient3d_exact;
using detail::orient3d_filtered;

namespace {

// The coplanar case: project onto a coordinate plane in which the triangles keep their area,
// turn both counter-clockwise there, and look for a separating edge (an edge of either
// triangle with the other's three vertices strictly outside). Closed convex polygons are
// disjoint exactly when there is one.
bool coplanar_intersect(glm::dvec3 t1[3], glm::dvec3 t2[3]) {
  const glm::dvec3 n = glm::cross(t1[1] - t1[0], t1[2] - t1[0]);  // only to try the best plane first
  int axes[3] = {0, 1, 2};
  std::sort(axes, axes + 3, [&](int p, int q) { return std::abs(n[p]) > std::abs(n[q]); });
  int i = 0, j = 1, o1 = 0;
  for (int drop : axes) {
    i = (drop + 1) % 3;
    j = (drop + 2) % 3;
    o1 = orient2d(t1[0], t1[1], t1[2], i, j);
    if (o1 != 0) break;
  }
  if (o1 == 0) return false;  // degenerate: not called for those
  if (o1 < 0) std::swap(t1[1], t1[2]);
  const int o2 = orient2d(t2[0], t2[1], t2[2], i, j);
  if (o2 == 0) return false;
  if (o2 < 0) std::swap(t2[1], t2[2]);
  auto separated = [&](const glm::dvec3* edges, const glm::dvec3* other) {
    for (int e = 0; e < 3; ++e) {
      const glm::dvec3& p = edges[e];
      const glm::dvec3& q = edges[(e + 1) % 3];
      if (orient2d(p, q, other[0], i, j) < 0 && orient2d(p, q, other[1], i, j) < 0 &&
          orient2d(p, q, other[2], i, j) < 0)
        return true;
    }
    return false;
  };
  return !separated(t1, t2) && !separated(t2, t1);
}

// Of a triangle whose vertices have the signs s (not all equal and non-zero, not all zero)
// with respect to the other's plane: the vertex `apex` and the factor `flip` (+1 or -1) such
// that flip * s[apex] >= 0 and the other two have flip * s <= 0, the apex strictly off the
// plane whenever possible. The chord of the triangle in the other plane then runs from the
// edge apex-next to the edge apex-next-next, neither lying in that plane.
void choose_apex(const int s[3], int& apex, int& flip) {
  for (int k = 0; k < 3; ++k) {
    if (s[k] == 0) continue;
    if (s[k] * s[(k + 1) % 3] <= 0 && s[k] * s[(k + 2) % 3] <= 0) {
      apex = k;
      flip = s[k];
      return;
    }
  }
  // One vertex on the plane, the other two strictly on one side: the chord is that vertex.
  for (int k = 0; k < 3; ++k)
    if (s[k] == 0) {
      apex = k;
      flip = -s[(k + 1) % 3];
      return;
    }
}

// A cheap certain "no" for two nearly coplanar triangles, which the orientation filter cannot
// tell apart: projected on an axis in T1's plane across one of the six edges, the two are
// apart by more than any rounding of the projections (|fl(a.v) - a.v| <= 3 eps sum |a_i v_i|,
// taken with a wide margin). The axes need no accuracy: any axis that separates will do.
bool separated_in_plane(const glm::dvec3 t1[3], const glm::dvec3 t2[3]) {
  const glm::dvec3 n = glm::cross(t1[1] - t1[0], t1[2] - t1[0]);
  glm::dvec3 extent(0);
  for (int k = 0; k < 3; ++k) extent = glm::max(extent, glm::max(glm::abs(t1[k]), glm::abs(t2[k])));
  for (int e = 0; e < 6; ++e) {
    const glm::dvec3* t = e < 3 ? t1 : t2;
    const glm::dvec3 axis = glm::cross(n, t[(e + 1) % 3] - t[e % 3]);
    const double margin = 16 * kEps * glm::dot(glm::abs(axis), extent);
    double lo1 = glm::dot(axis, t1[0]), hi1 = lo1, lo2 = glm::dot(axis, t2[0]), hi2 = lo2;
    for (int k = 1; k < 3; ++k) {
      const double p1 = glm::dot(axis, t1[k]), p2 = glm::dot(axis, t2[k]);
      lo1 = std::min(lo1, p1);
      hi1 = std::max(hi1, p1);
      lo2 = std::min(lo2, p2);
      hi2 = std::max(hi2, p2);
    }
    if (hi1 + 2 * margin < lo2 || hi2 + 2 * margin < lo1) return true;
  }
  return false;
}

}  // namespace

bool triangles_intersect(const glm::dvec3& a1, const glm::dvec3& b1, const glm::dvec3& c1, const glm::dvec3& a2,
                         const glm::dvec3& b2, const glm::dvec3& c2) {
  glm::dvec3 t1[3] = {a1, b1, c1}, t2[3] = {a2, b2, c2};
  // T1's vertices against T2's plane: all strictly on one side, no contact.
  int s1[3];
  bool uncertain = false;
  for (int k = 0; k < 3; ++k) {
    s1[k] = orient3d_filtered(t2[0], t2[1], t2[2], t1[k]);
    uncertain = uncertain || s1[k] == kUncertain;
  }
  if (uncertain) {
    // Nearly coplanar (a flat cloth, neighbours in a smooth one): first the cheap way out.
    if (separated_in_plane(t1, t2)) return false;
    for (int k = 0; k < 3; ++k)
      if (s1[k] == kUncertain) s1[k] = -orient3d_exact(t2[0], t2[1], t2[2], t1[k]);
  }
  if ((s1[0] > 0 && s1[1] > 0 && s1[2] > 0) || (s1[0] < 0 && s1[1] < 0 && s1[2] < 0)) return false;
  if (s1[0] == 0 && s1[1] == 0 && s1[2] == 0) return coplanar_intersect(t1, t2);
  int s2[3];
  for (int k = 0; k < 3; ++k) s2[k] = orient3d(t1[0], t1[1], t1[2], t2[k]);
  if ((s2[0] > 0 && s2[1] > 0 && s2[2] > 0) || (s2[0] < 0 && s2[1] < 0 && s2[2] < 0)) return false;
  // Each triangle meets the other's plane in a chord on their common line L. Arrange both
  // (Devillers & Guigue): T1 rotated so its apex A1 is alone on the non-negative side of T2's
  // plane, T2 reversed if needed to make that side the positive one; likewise T2's apex A2 on
  // the positive side of T1's plane, T1's other two vertices swapped if needed. Then along
  // L's direction n1 x n2 T1's chord runs from Y1 (on A1C1) to X1 (on A1B1) and T2's from X2
  // (on A2B2) to Y2 (on A2C2), and orient3d(A1, B1, A2, B2) has the sign of X1 - X2 along L,
  // orient3d(A1, C1, C2, A2) that of Y2 - Y1: the chords overlap when neither is positive.
  int i = 0, f = 1, j = 0, g = 1;
  choose_apex(s1, i, f);
  choose_apex(s2, j, g);
  const glm::dvec3& A1 = t1[i];
  const glm::dvec3& B1 = t1[g > 0 ? (i + 1) % 3 : (i + 2) % 3];
  const glm::dvec3& C1 = t1[g > 0 ? (i + 2) % 3 : (i + 1) % 3];
  const glm::dvec3& A2 = t2[j];
  const glm::dvec3& B2 = t2[f > 0 ? (j + 1) % 3 : (j + 2) % 3];
  const glm::dvec3& C2 = t2[f > 0 ? (j + 2) % 3 : (j + 1) % 3];
  return orient3d(A1, B1, A2, B2) <= 0 && orient3d(A1, C1, C2, A2) <= 0;
}

}  // namespace exact

namespace {

struct Box {
  glm::dvec3 lo, hi;
};
struct CellRange {
  int32_t lo[3], hi[3];
};
// One triangle in one cell, with what the pair loop looks at kept at hand (no random access
// until a pair's boxes overlap).
struct Entry {
  int32_t cell[3];
  int32_t lo[3];                   // the triangle's first cell, for the first-shared-cell rule
  float box[6];                    // its bounding box rounded outwards: lo xyz, hi xyz
  std::array<uint32_t, 3> vertex;  // its vertex indices
};
inline float round_down(double v) {
  float f = float(v);
  return double(f) > v ? std::nextafter(f, -HUGE_VALF) : f;
}
inline float round_up(double v) {
  float f = float(v);
  return double(f) < v ? std::nextafter(f, HUGE_VALF) : f;
}
inline bool overlap(const float* a, const float* b) {
  return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}

constexpr int kMaxCells = 64;          // a box over more cells goes to the large list
constexpr double kMaxCoord = 0x1p30;   // cell coordinates beyond this: the large list too

inline bool overlap(const Box& a, const Box& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}
inline bool share_vertex(const std::array<uint32_t, 3>& a, const std::array<uint32_t, 3>& b) {
  for (uint32_t u : a)
    if (u == b[0] || u == b[1] || u == b[2]) return true;
  return false;
}
inline uint64_t cell_hash(const int32_t c[3]) {
  uint64_t k = uint64_t(uint32_t(c[0])) * 0x9E3779B97F4A7C15ull;
  k ^= uint64_t(uint32_t(c[1])) * 0xC2B2AE3D27D4EB4Full;
  k ^= uint64_t(uint32_t(c[2])) * 0x165667B19E3779F9ull;
  return k ^ (k >> 29) ^ (k >> 47);
}

}  // namespace

size_t count_self_intersections(const std::vector<std::array<uint32_t, 3>>& triangles,
                                const std::vector<glm::dvec3>& positions) {
  // The triangles that take part: finite and of non-zero area.
  std::vector<std::array<uint32_t, 3>> tri;
  std::vector<Box> box;
  double edge_sum = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& ix = triangles[t];
    for (uint32_t v : ix)
      if (v >= positions.size())
        throw std::invalid_argument(fmt::format("count_self_intersections: triangle {} has vertex {} of {} positions",
                                                t, v, positions.size()));
    const glm::dvec3& a = positions[ix[0]];
    const glm::dvec3& b = positions[ix[1]];
    const glm::dvec3& c = positions[ix[2]];
    bool finite = true;
    for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(a[k]) && std::isfinite(b[k]) && std::isfinite(c[k]);
    if (!finite || exact::degenerate(a, b, c)) continue;
    tri.push_back(ix);
    box.push_back({glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))});
    edge_sum += glm::length(b - a) + glm::length(c - b) + glm::length(a - c);
  }
  const size_t n = tri.size();
  if (n < 2) return 0;

  size_t count = 0;
  auto intersect = [&](const std::array<uint32_t, 3>& u, const std::array<uint32_t, 3>& v) {
    count += exact::triangles_intersect(positions[u[0]], positions[u[1]], positions[u[2]], positions[v[0]],
                                        positions[v[1]], positions[v[2]]);
  };

  // Cells of twice the mean edge length; each triangle's range of cells.
  double cell = 2 * edge_sum / (3.0 * double(n));
  if (!(cell > 0) || !std::isfinite(cell)) cell = 1;  // a sum that overflowed: any size is correct
  const double inv = 1 / cell;
  std::vector<CellRange> range(n);
  std::vector<uint32_t> large;
  size_t entries = 0;
  for (uint32_t t = 0; t < n; ++t) {
    bool fits = true;
    int64_t cells = 1;
    for (int k = 0; k < 3; ++k) {
      const double lo = std::floor(box[t].lo[k] * inv), hi = std::floor(box[t].hi[k] * inv);
      if (!(lo >= -kMaxCoord && hi <= kMaxCoord)) {
        fits = false;
        break;
      }
      range[t].lo[k] = int32_t(lo);
      range[t].hi[k] = int32_t(hi);
      cells *= int64_t(hi - lo + 1);
      if (cells > kMaxCells) {
        fits = false;
        break;
      }
    }
    if (fits)
      entries += size_t(cells);
    else
      large.push_back(t);
  }

  // The buckets: a counting sort of (cell, triangle) entries, in triangle order. When the cells
  // around the triangles are few enough, each cell is its own bucket, numbered row by row (no
  // collisions, and neighbouring triangles write near each other); else a hash of the cell.
  std::vector<uint8_t> is_large(n, 0);
  for (uint32_t t : large) is_large[t] = 1;
  int64_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, dim[3] = {0, 0, 0};
  for (uint32_t t = 0; t < n; ++t)
    if (!is_large[t])
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min<int64_t>(lo[k], range[t].lo[k]);
        dim[k] = std::max<int64_t>(dim[k], range[t].hi[k]);  // the highest cell, for now
      }
  for (int k = 0; k < 3; ++k) dim[k] = dim[k] - lo[k] + 1;
  const double dense = double(dim[0]) * double(dim[1]) * double(dim[2]);
  const bool direct = entries > 0 && dense <= 4.0 * double(entries) + 1024;
  size_t buckets = 16;
  if (direct)
    buckets = size_t(dense);
  else
    while (buckets < 2 * entries) buckets *= 2;
  const uint64_t mask = buckets - 1;
  auto bucket = [&](const int32_t* c) -> size_t {
    if (direct) return size_t(((c[2] - lo[2]) * dim[1] + (c[1] - lo[1])) * dim[0] + (c[0] - lo[0]));
    return cell_hash(c) & mask;
  };
  std::vector<uint32_t> start(buckets + 1, 0);
  auto for_cells = [&](uint32_t t, auto&& visit) {
    const CellRange& r = range[t];
    int32_t c[3];
    for (c[2] = r.lo[2]; c[2] <= r.hi[2]; ++c[2])
      for (c[1] = r.lo[1]; c[1] <= r.hi[1]; ++c[1])
        for (c[0] = r.lo[0]; c[0] <= r.hi[0]; ++c[0]) visit(c);
  };
  for (uint32_t t = 0; t < n; ++t)
    if (!is_large[t]) for_cells(t, [&](const int32_t* c) { ++start[bucket(c) + 1]; });
  for (size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<Entry> entry(entries);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t t = 0; t < n; ++t)
      if (!is_large[t]) {
        const int32_t* first = range[t].lo;
        const Box& bx = box[t];
        const Entry proto{{0, 0, 0}, {first[0], first[1], first[2]},
                          {round_down(bx.lo.x), round_down(bx.lo.y), round_down(bx.lo.z), round_up(bx.hi.x),
                           round_up(bx.hi.y), round_up(bx.hi.z)},
                          tri[t]};
        for_cells(t, [&](const int32_t* c) {
          Entry& e = entry[fill[bucket(c)]++];
          e = proto;
          for (int k = 0; k < 3; ++k) e.cell[k] = c[k];
        });
      }
  }

  // Pairs in a cell, each tested only in the first cell (lowest x, y, z) the two ranges share.
  for (size_t b = 0; b < buckets; ++b) {
    for (uint32_t e = start[b]; e < start[b + 1]; ++e) {
      const Entry& p = entry[e];
      for (uint32_t f = e + 1; f < start[b + 1]; ++f) {
        const Entry& q = entry[f];
        if (q.cell[0] != p.cell[0] || q.cell[1] != p.cell[1] || q.cell[2] != p.cell[2]) continue;  // a collision
        if (std::max(p.lo[0], q.lo[0]) != p.cell[0] || std::max(p.lo[1], q.lo[1]) != p.cell[1] ||
            std::max(p.lo[2], q.lo[2]) != p.cell[2] || !overlap(p.box, q.box) || share_vertex(p.vertex, q.vertex))
          continue;
        intersect(p.vertex, q.vertex);
      }
    }
  }
  // The large triangles against every other (two large ones once).
  for (uint32_t l : large)
    for (uint32_t t = 0; t < n; ++t)
      if (t != l && (!is_large[t] || t > l) && overlap(box[l], box[t]) && !share_vertex(tri[l], tri[t]))
        intersect(tri[l], tri[t]);
  return count;
}

size_t count_self_intersections(const ClothModel& model, const ClothSnapshot& snapshot) {
  if (snapshot.pos.size() != model.initial.size())
    throw std::invalid_argument(fmt::format("count_self_intersections: {} positions for a cloth of {} particles",
                                            snapshot.pos.size(), model.initial.size()));
  std::vector<glm::dvec3> positions;
  positions.reserve(snapshot.pos.size());
  for (const glm::dvec4& p : snapshot.pos) positions.emplace_back(p.x, p.y, p.z);
  return count_self_intersections(model.triangles, positions);
}

}  // namespace clothsim

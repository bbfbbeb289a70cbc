// Exact self-intersection count (intersections.hpp): orientation predicates with a static
// filter and an exact expansion fallback, Devillers-Guigue's triangle pair test on them, and a
// uniform spatial hash of the triangles' bounding boxes.
//
// The expansion arithmetic follows J. R. Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates" (1997): an expansion is a sum of doubles,
// non-overlapping and in increasing magnitude, whose largest component has the sign of the sum.
// Two-sum, two-diff and Dekker's two-product are error-free (a + b = x + y exactly) provided
// nothing overflows or underflows, and the project compiles with -ffp-contract=off, so no
// multiply-add is fused behind our back.
#include "intersections.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace clothsim {
namespace exact {
namespace {

constexpr double kEps = 0x1p-53;               // half an ulp of 1: the unit roundoff
constexpr double kSplitter = 0x1p27 + 1.0;     // Dekker's split of a 53-bit significand in two halves
constexpr double kO2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kO3dBound = (7.0 + 56.0 * kEps) * kEps;

// a + b = x + y exactly, |y| <= ulp(x) / 2.
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}
// a - b = x + y exactly.
inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double bv = a - x;
  const double av = x + bv;
  y = (a - av) + (bv - b);
}
inline void split(double a, double& hi, double& lo) {
  const double c = kSplitter * a;
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}
// a * b = x + y exactly (Dekker).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  const double e1 = x - ahi * bhi;
  const double e2 = e1 - alo * bhi;
  const double e3 = e2 - ahi * blo;
  y = alo * blo - e3;
}

// An expansion of at most N components (zeros eliminated), smallest first.
template <int N> struct Expansion {
  double c[N];
  int n = 0;
  void push(double v) {
    if (v != 0) c[n++] = v;
  }
  int sign() const { return n == 0 ? 0 : (c[n - 1] > 0 ? 1 : -1); }
};

// h += b in place (Shewchuk's Grow-Expansion with zero elimination): component i is read
// before anything is written at i, and at most one component is added.
template <int N> void grow(Expansion<N>& h, double b) {
  double q = b;
  int out = 0;
  for (int i = 0; i < h.n; ++i) {
    double s, err;
    two_sum(q, h.c[i], s, err);
    if (err != 0) h.c[out++] = err;
    q = s;
  }
  h.n = out;
  h.push(q);
}
// h += f, growing h with each component of f in turn; the caller's N bounds the result.
template <int N, int K> void add(Expansion<N>& h, const Expansion<K>& f) {
  for (int k = 0; k < f.n; ++k) grow(h, f.c[k]);
}
template <int N, int M, int K> Expansion<N> sum(const Expansion<M>& e, const Expansion<K>& f) {
  static_assert(N >= M + K);
  Expansion<N> h;
  for (int i = 0; i < e.n; ++i) h.c[i] = e.c[i];
  h.n = e.n;
  add(h, f);
  return h;
}
template <int N> Expansion<N> negate(Expansion<N> e) {
  for (int i = 0; i < e.n; ++i) e.c[i] = -e.c[i];
  return e;
}
// e * b (Scale-Expansion with zero elimination, two-sums throughout).
template <int N, int M> Expansion<N> scale(const Expansion<M>& e, double b) {
  static_assert(N >= 2 * M);
  Expansion<N> h;
  if (e.n == 0 || b == 0) return h;
  double q, err;
  two_product(e.c[0], b, q, err);
  h.push(err);
  for (int i = 1; i < e.n; ++i) {
    double p, perr, s;
    two_product(e.c[i], b, p, perr);
    two_sum(q, perr, s, err);
    h.push(err);
    two_sum(p, s, q, err);
    h.push(err);
  }
  h.push(q);
  return h;
}
// e * f: the sum of e scaled by each component of f.
template <int N, int M, int K> Expansion<N> product(const Expansion<M>& e, const Expansion<K>& f) {
  static_assert(N >= 2 * M * K);
  Expansion<N> h;
  for (int k = 0; k < f.n; ++k) add(h, scale<2 * M>(e, f.c[k]));
  return h;
}
Expansion<2> difference(double a, double b) {
  double x, y;
  two_diff(a, b, x, y);
  Expansion<2> e;
  e.push(y);
  e.push(x);
  return e;
}

// The exact sign of (ax - cx)(by - cy) - (ay - cy)(bx - cx).
int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  const Expansion<2> acx = difference(ax, cx), acy = difference(ay, cy);
  const Expansion<2> bcx = difference(bx, cx), bcy = difference(by, cy);
  const Expansion<8> left = product<8>(acx, bcy), right = product<8>(acy, bcx);
  return sum<16>(left, negate(right)).sign();
}

// The exact sign of Shewchuk's orient3d(a, b, c, d) = det[a - d, b - d, c - d].
int orient3d_exact(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  const Expansion<2> adx = difference(a.x, d.x), ady = difference(a.y, d.y), adz = difference(a.z, d.z);
  const Expansion<2> bdx = difference(b.x, d.x), bdy = difference(b.y, d.y), bdz = difference(b.z, d.z);
  const Expansion<2> cdx = difference(c.x, d.x), cdy = difference(c.y, d.y), cdz = difference(c.z, d.z);
  // The three 2x2 minors, each an expansion of at most 16 components.
  const Expansion<16> bc = sum<16>(product<8>(bdx, cdy), negate(product<8>(cdx, bdy)));
  const Expansion<16> ca = sum<16>(product<8>(cdx, ady), negate(product<8>(adx, cdy)));
  const Expansion<16> ab = sum<16>(product<8>(adx, bdy), negate(product<8>(bdx, ady)));
  const Expansion<64> ta = product<64>(bc, adz), tb = product<64>(ca, bdz), tc = product<64>(ab, cdz);
  return sum<192>(sum<128>(ta, tb), tc).sign();
}

inline int sign_of(double v) { return (v > 0) - (v < 0); }

constexpr int kUncertain = 2;

// orient3d in double with Shewchuk's static error bound: the exact sign, or kUncertain.
int orient3d_filtered(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  // Shewchuk's orient3d(a, b, c, d) = det[a - d, b - d, c - d] = -det[b - a, c - a, d - a],
  // evaluated in this order so that his error bound holds.
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double adz = a.z - d.z, bdz = b.z - d.z, cdz = c.z - d.z;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  if (std::abs(det) > kO3dBound * permanent) return -sign_of(det);
  // Every product of differences is exactly zero (no underflow assumed): so is the determinant.
  if (permanent == 0) return 0;
  return kUncertain;
}

}  // namespace

int orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  const int s = orient3d_filtered(a, b, c, d);
  return s != kUncertain ? s : -orient3d_exact(a, b, c, d);
}

int orient2d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int i, int j) {
  const double left = (a[i] - c[i]) * (b[j] - c[j]);
  const double right = (a[j] - c[j]) * (b[i] - c[i]);
  const double det = left - right;
  const double permanent = std::abs(left) + std::abs(right);
  if (std::abs(det) > kO2dBound * permanent) return sign_of(det);
  if (permanent == 0) return 0;
  return orient2d_exact(a[i], a[j], b[i], b[j], c[i], c[j]);
}

bool degenerate(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return orient2d(a, b, c, 0, 1) == 0 && orient2d(a, b, c, 1, 2) == 0 && orient2d(a, b, c, 2, 0) == 0;
}

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

// The exact orientation predicates of the self-intersection count (intersections.hpp):
// orient3d and orient2d in double with a static filter and an exact expansion fallback.
//
// The expansion arithmetic follows J. R. Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates" (1997): an expansion is a sum of doubles,
// non-overlapping and in increasing magnitude, whose largest component has the sign of the sum.
// Two-sum, two-diff and Dekker's two-product are error-free (a + b = x + y exactly) provided
// nothing overflows or underflows, and the project compiles with -ffp-contract=off, so no
// multiply-add is fused behind our back.
#include "analysis/exact_predicates.hpp"

#include <cmath>

#include "analysis/intersections.hpp"

namespace clothsim {
namespace exact {
namespace {

using detail::kEps;

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
inline int sign_of(double v) { return (v > 0) - (v < 0); }

}  // namespace

namespace detail {

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

}  // namespace detail

using detail::kUncertain;

int orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  const int s = detail::orient3d_filtered(a, b, c, d);
  return s != kUncertain ? s : -detail::orient3d_exact(a, b, c, d);
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
}  // namespace exact
}  // namespace clothsim

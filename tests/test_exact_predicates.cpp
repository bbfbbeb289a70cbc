// The exact predicates under the self-intersection count (intersections.hpp: orient3d, orient2d,
// triangles_intersect; exact_predicates.cpp): the pair
// test against an integer separating-axis reference on soups full of degeneracies, orient3d and
// orient2d where plain doubles round to the wrong sign, and a triangle touching another at a
// point of its face or edge. Points are integers in units of 2^-52 near 1, so exact integer
// arithmetic knows every determinant.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "intersection_fixtures.hpp"
#include "analysis/intersections.hpp"

using namespace clothsim;
using test::Mesh;
using test::Rng;

namespace {

// Integer points and the separating-axis reference: closed triangles (non-degenerate) are
// disjoint exactly when their projections on one of n1, n2, e1 x e2, n1 x e, n2 x e are.
struct IV {
  int64_t x, y, z;
};
IV operator-(IV a, IV b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
IV cross(IV a, IV b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
int64_t dot(IV a, IV b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
bool zero(IV a) { return a.x == 0 && a.y == 0 && a.z == 0; }
bool sat_intersect(const IV t1[3], const IV t2[3]) {
  const IV e1[3] = {t1[1] - t1[0], t1[2] - t1[1], t1[0] - t1[2]};
  const IV e2[3] = {t2[1] - t2[0], t2[2] - t2[1], t2[0] - t2[2]};
  const IV n1 = cross(e1[0], e1[1]), n2 = cross(e2[0], e2[1]);
  std::vector<IV> axes = {n1, n2};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) axes.push_back(cross(e1[i], e2[j]));
    axes.push_back(cross(n1, e1[i]));
    axes.push_back(cross(n1, e2[i]));
    axes.push_back(cross(n2, e1[i]));
    axes.push_back(cross(n2, e2[i]));
  }
  for (const IV& a : axes) {
    if (zero(a)) continue;
    int64_t lo1 = INT64_MAX, hi1 = INT64_MIN, lo2 = INT64_MAX, hi2 = INT64_MIN;
    for (int k = 0; k < 3; ++k) {
      lo1 = std::min(lo1, dot(a, t1[k]));
      hi1 = std::max(hi1, dot(a, t1[k]));
      lo2 = std::min(lo2, dot(a, t2[k]));
      hi2 = std::max(hi2, dot(a, t2[k]));
    }
    if (hi1 < lo2 || hi2 < lo1) return false;
  }
  return true;
}
glm::dvec3 to_d(IV a) { return glm::dvec3(double(a.x), double(a.y), double(a.z)); }

// Points 1 + k * 2^-52: doubles in [1, 2) that are integers k in units of their ulp, so exact
// integer arithmetic knows every determinant, while the doubles' products round.
constexpr double kUnit = 0x1p-52;
glm::dvec3 at_units(const IV& k) { return glm::dvec3(1 + double(k.x) * kUnit, 1 + double(k.y) * kUnit, 1 + double(k.z) * kUnit); }
IV add(IV a, IV b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
IV mul(int64_t s, IV a) { return {s * a.x, s * a.y, s * a.z}; }
// The sign of (u x v) . w in exact integers (u, v below 2^49, w small: fits an __int128). It is
// det[u, v, w], and so det[b - a, c - a, d - a] for b = a + u, c = a + v and d = a + s u + t v + w.
int cross_dot_sign(IV u, IV v, IV w) {
  using L = __int128;
  const L det = (L(u.y) * v.z - L(u.z) * v.y) * w.x + (L(u.z) * v.x - L(u.x) * v.z) * w.y +
                (L(u.x) * v.y - L(u.y) * v.x) * w.z;
  return (det > 0) - (det < 0);
}
// The same determinant as plain doubles would have it.
int naive_sign(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  const double det = glm::dot(glm::cross(b - a, c - a), d - a);
  return (det > 0) - (det < 0);
}
IV random_units(Rng& r, int64_t range) {
  auto one = [&] { return int64_t(r.uniform() * double(range)); };
  const int64_t x = one(), y = one(), z = one();
  return {x, y, z};
}
IV signed_units(Rng& r, int64_t half) { return random_units(r, 2 * half) - IV{half, half, half}; }
IV nudge(Rng& r) {
  const int64_t x = r.below(3) - 1, y = r.below(3) - 1, z = r.below(3) - 1;
  return {x, y, z};
}

}  // namespace

TEST_CASE("small-integer soups full of degeneracies: the pair test is the separating-axis reference's",
          "[intersections]") {
  // Coordinates in {0, ..., 3}: vertices on faces, edges on edges, coplanar pairs galore.
  Rng r(7);
  std::vector<std::array<IV, 3>> tris;
  while (tris.size() < 400) {
    std::array<IV, 3> t;
    for (auto& v : t) {
      const int64_t x = r.below(4), y = r.below(4), z = r.below(4);
      v = {x, y, z};
    }
    if (!zero(cross(t[1] - t[0], t[2] - t[0]))) tris.push_back(t);
  }
  size_t disagree = 0, hits = 0, coplanar = 0;
  for (size_t i = 0; i < tris.size(); ++i)
    for (size_t j = i + 1; j < tris.size(); ++j) {
      const auto& a = tris[i];
      const auto& b = tris[j];
      const bool want = sat_intersect(a.data(), b.data());
      const bool got = exact::triangles_intersect(to_d(a[0]), to_d(a[1]), to_d(a[2]), to_d(b[0]), to_d(b[1]), to_d(b[2]));
      disagree += want != got;
      hits += want;
      const IV n = cross(a[1] - a[0], a[2] - a[0]);
      coplanar += dot(n, b[0] - a[0]) == 0 && dot(n, b[1] - a[0]) == 0 && dot(n, b[2] - a[0]) == 0;
    }
  WARN("integer soup: " << hits << " of " << tris.size() * (tris.size() - 1) / 2 << " pairs intersect, " << coplanar
                        << " coplanar");
  CHECK(coplanar > 100);
  CHECK(disagree == 0);
  // The same soup through the hash (its boxes on cell boundaries), scaled to make the cells
  // small against the soup and with every triangle its own vertices.
  Mesh m;
  for (const auto& t : tris) {
    const auto base = uint32_t(m.pos.size());
    for (const IV& v : t) m.pos.push_back(0.375 * to_d(v));  // exact: the same geometry
    m.tri.push_back({base, base + 1, base + 2});
  }
  CHECK(m.count() == hits);
}

TEST_CASE("orient3d is exact where doubles round to the wrong sign", "[intersections]") {
  Rng r(99);
  int wrong = 0;
  const int64_t base = int64_t(1) << 50, span = int64_t(1) << 47;
  for (int trial = 0; trial < 2000; ++trial) {
    // a near 1.25, b = a + u and c = a + v up to 2^47 units (0.03) away; d in their plane
    // (a + s u + t v), then nudged by -1, 0 or +1 unit per coordinate: det = (u x v) . nudge.
    const IV a = add(IV{base, base, base}, random_units(r, span)), u = signed_units(r, span), v = signed_units(r, span);
    const IV w = nudge(r);
    const IV d = add(add(add(a, mul(r.below(3), u)), mul(r.below(3) - 1, v)), w);
    const glm::dvec3 A = at_units(a), B = at_units(add(a, u)), C = at_units(add(a, v)), D = at_units(d);
    const int want = cross_dot_sign(u, v, w);
    REQUIRE(exact::orient3d(A, B, C, D) == want);
    REQUIRE(exact::orient3d(B, C, A, D) == want);
    REQUIRE(exact::orient3d(B, A, C, D) == -want);
    REQUIRE(exact::orient3d(D, A, B, C) == -want);
    wrong += naive_sign(A, B, C, D) != want;
    // orient2d on the (x, y) projection: e on the line ab past b, nudged: (u x (2u + w)).z = (u x w).z.
    const IV e = add(add(a, mul(2, u)), w);
    const int want2 = cross_dot_sign(u, w, {0, 0, 1});
    REQUIRE(exact::orient2d(A, B, at_units(e), 0, 1) == want2);
    REQUIRE(exact::orient2d(B, at_units(e), A, 0, 1) == want2);
    REQUIRE(exact::orient2d(at_units(e), B, A, 0, 1) == -want2);
  }
  WARN("plain doubles got the sign of orient3d wrong " << wrong << " times in 2000");
  CHECK(wrong > 20);
}

TEST_CASE("a triangle touching another at a point of its face or edge: the exact answer", "[intersections]") {
  // T1 = (P, P + 4A, P + 4B) in units of 2^-52 near 1: its interior point P + A + B, the
  // midpoint of an edge P + 2A, the point P + 6A on that edge's line past its end and P - A - B
  // past its corner are all exact doubles. T2 has a vertex at one of them, its other two
  // vertices well to one side of T1's plane: it touches T1 there, or misses it.
  Rng r(2024);
  int naive_wrong = 0, cases = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const IV p = add(random_units(r, int64_t(1) << 48), {int64_t(1) << 49, int64_t(1) << 49, int64_t(1) << 49});
    const IV a = random_units(r, int64_t(1) << 44), b = random_units(r, int64_t(1) << 44);
    const glm::dvec3 P = at_units(p), Q = at_units(add(p, mul(4, a))), R = at_units(add(p, mul(4, b)));
    const int up = cross_dot_sign(a, b, {0, 0, 1});  // which way one unit more z moves a point off the plane
    if (up == 0) continue;
    const glm::dvec3 n = glm::normalize(glm::cross(Q - P, R - P));
    struct Case {
      IV at;
      int nudge;  // units of z added
      size_t expected;
    };
    const Case touch[] = {
        {add(add(p, a), b), 0, 1},            // inside the face
        {add(p, mul(2, a)), 0, 1},            // on an edge
        {add(p, mul(6, a)), 0, 0},            // on the edge's line, past its end
        {add(add(p, mul(-1, a)), mul(-1, b)), 0, 0},  // in the plane, past a corner
        {add(add(p, a), b), up, 0},           // one unit off the face, on T2's side
        {add(add(p, a), b), -up, 1},          // one unit through the face
    };
    for (const Case& k : touch) {
      IV at = k.at;
      at.z += k.nudge;
      const glm::dvec3 M = at_units(at);
      // T2's other vertices 1 cm off the plane (the side of +n) and apart.
      const glm::dvec3 t = glm::normalize(Q - P);
      Mesh m;
      m.pos = {P, Q, R, M, M + 0.01 * n + 0.003 * t, M + 0.01 * n - 0.002 * t + 0.002 * glm::cross(n, t)};
      m.tri = {{0, 1, 2}, {3, 4, 5}};
      INFO("trial " << trial << ", vertex at (" << at.x << ", " << at.y << ", " << at.z << ") units");
      REQUIRE(m.count() == k.expected);
      // The same pair given the other way round and rotated.
      REQUIRE(exact::triangles_intersect(m.pos[4], m.pos[5], m.pos[3], R, P, Q) == (k.expected == 1));
      ++cases;
      naive_wrong += naive_sign(P, Q, R, M) != k.nudge * up;  // det = 16 (a x b) . (0, 0, nudge)
    }
  }
  WARN("plain doubles put T2's vertex on the wrong side of T1's plane in " << naive_wrong << " of " << cases
                                                                          << " cases");
  CHECK(naive_wrong > 50);
}

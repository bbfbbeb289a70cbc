// The exact self-intersection count (intersections.hpp): grids and folds that never touch,
// single pairs (crossing, missing, sharing a vertex, coplanar), two sheets pushed through each
// other against an independent brute force, random soups against the O(n^2) count, a real
// cloth at rest, and the time for a 256 x 256 grid. The exact predicates underneath are
// tested in test_exact_predicates.cpp.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "intersection_fixtures.hpp"
#include "analysis/intersections.hpp"
#include "test_helpers.hpp"

using namespace clothsim;
using test::Mesh;
using test::Points;
using test::Tris;
using test::Rng;

namespace {

// An nx x ny grid laid out like the CS184 grid (i = y * nx + x), two triangles per cell,
// (A, C, B) and (B, C, D) with A = (x, y), B = (x + 1, y), C = (x, y + 1), D = (x + 1, y + 1);
// vertex (x, y) at place(x, y).
Mesh grid(int nx, int ny, const std::function<glm::dvec3(int, int)>& place) {
  Mesh m;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) m.pos.push_back(place(x, y));
  for (int y = 0; y + 1 < ny; ++y)
    for (int x = 0; x + 1 < nx; ++x) {
      const auto a = uint32_t(y * nx + x), b = a + 1, c = a + uint32_t(nx), d = c + 1;
      m.tri.push_back({a, c, b});
      m.tri.push_back({b, c, d});
    }
  return m;
}

// The O(n^2) count with the same pair test: what the hash must reproduce.
size_t brute_force(const Mesh& m) {
  std::vector<uint32_t> ok;
  for (uint32_t t = 0; t < m.tri.size(); ++t) {
    bool finite = true;
    for (uint32_t v : m.tri[t])
      for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(m.pos[v][k]);
    if (finite && !exact::degenerate(m.pos[m.tri[t][0]], m.pos[m.tri[t][1]], m.pos[m.tri[t][2]])) ok.push_back(t);
  }
  size_t n = 0;
  for (size_t i = 0; i < ok.size(); ++i)
    for (size_t j = i + 1; j < ok.size(); ++j) {
      const auto& u = m.tri[ok[i]];
      const auto& v = m.tri[ok[j]];
      bool share = false;
      for (uint32_t a : u) share = share || a == v[0] || a == v[1] || a == v[2];
      if (share) continue;
      n += exact::triangles_intersect(m.pos[u[0]], m.pos[u[1]], m.pos[u[2]], m.pos[v[0]], m.pos[v[1]], m.pos[v[2]]);
    }
  return n;
}

// An independent test for generic positions, in plain doubles: two triangles intersect when
// an edge of one crosses the other (no vertex on the other's plane, no edge in it).
bool segment_crosses(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b,
                     const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double dp = glm::dot(n, p - a), dq = glm::dot(n, q - a);
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq) return false;
  const glm::dvec3 x = p + (dp / (dp - dq)) * (q - p);
  return glm::dot(n, glm::cross(b - a, x - a)) >= 0 && glm::dot(n, glm::cross(c - b, x - b)) >= 0 &&
         glm::dot(n, glm::cross(a - c, x - c)) >= 0;
}
size_t brute_force_segments(const Mesh& m) {
  size_t n = 0;
  for (size_t i = 0; i < m.tri.size(); ++i)
    for (size_t j = i + 1; j < m.tri.size(); ++j) {
      const auto& u = m.tri[i];
      const auto& v = m.tri[j];
      bool share = false;
      for (uint32_t a : u) share = share || a == v[0] || a == v[1] || a == v[2];
      if (share) continue;
      const glm::dvec3 P[3] = {m.pos[u[0]], m.pos[u[1]], m.pos[u[2]]};
      const glm::dvec3 Q[3] = {m.pos[v[0]], m.pos[v[1]], m.pos[v[2]]};
      bool hit = false;
      for (int e = 0; e < 3 && !hit; ++e)
        hit = segment_crosses(P[e], P[(e + 1) % 3], Q[0], Q[1], Q[2]) ||
              segment_crosses(Q[e], Q[(e + 1) % 3], P[0], P[1], P[2]);
      n += hit;
    }
  return n;
}

}  // namespace

TEST_CASE("a flat grid, a sheet folded with a gap and a far copy of it have no self-intersections", "[intersections]") {
  const Mesh flat = grid(33, 17, [](int x, int y) { return glm::dvec3(x * 0.03, 0.7, y * 0.03); });
  CHECK(flat.tri.size() == 32 * 16 * 2);
  CHECK(flat.count() == 0);

  // A strip folded over a half cylinder of radius 5 mm: two layers 1 cm apart.
  const double du = 0.0025, r = 0.005, a = 32 * du;
  auto fold = [&](int x, int y) {
    const double u = x * du, v = y * 0.01;
    if (u <= a) return glm::dvec3(u, v, 0.0);
    const double s = u - a;
    if (s <= M_PI * r) return glm::dvec3(a + r * std::sin(s / r), v, r - r * std::cos(s / r));
    return glm::dvec3(a - (s - M_PI * r), v, 2 * r);
  };
  Mesh folded = grid(77, 9, fold);
  CHECK(folded.count() == 0);
  // The layers do overlap in x and y: a little less gap and they would cross.
  Mesh squashed = grid(77, 9, [&](int x, int y) {
    glm::dvec3 p = fold(x, y);
    if (p.z > 1.5 * r) p.z = -0.001;  // the upper layer pushed below the lower one
    return p;
  });
  CHECK(squashed.count() > 0);

  Mesh two = folded;
  Mesh far = folded;
  for (auto& p : far.pos) p += glm::dvec3(1000.0, -250.0, 40.0);
  two.append(far);
  CHECK(two.count() == 0);
  // The copy laid through the first one instead counts across the parts.
  Mesh through = folded;
  Mesh crossing = grid(77, 9, [&](int x, int y) {
    const glm::dvec3 p = fold(x, y);
    return glm::dvec3(p.x + 0.0013, p.z - 0.0051, p.y + 0.0017);  // the strip turned on edge
  });
  through.append(crossing);
  CHECK(through.count() > 0);
  CHECK(through.count() == brute_force(through));
  // Both far apart: cells over a kilometre, too many to number one by one (the hashed buckets).
  Mesh twice = through;
  Mesh far_through = through;
  for (auto& p : far_through.pos) p += glm::dvec3(1000.0, -250.0, 40.0);
  twice.append(far_through);
  CHECK(twice.count() == 2 * through.count());
}

TEST_CASE("single pairs: crossing, missing, sharing a vertex, coplanar", "[intersections]") {
  const Points horizontal = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  auto pair = [&](Points second, std::array<uint32_t, 3> idx = {3, 4, 5}) {
    Mesh m;
    m.pos = horizontal;
    m.pos.insert(m.pos.end(), second.begin(), second.end());
    m.tri = {{0, 1, 2}, idx};
    return m;
  };
  // A vertical triangle piercing the horizontal one.
  const Points vertical = {{0.2, 0.2, -0.5}, {0.2, 0.2, 0.5}, {0.4, 0.3, 0.0}};
  CHECK(pair(vertical).count() == 1);
  Points missing = vertical;
  for (auto& p : missing) p += glm::dvec3(0.7, 0.7, 0.0);
  CHECK(pair(missing).count() == 0);
  Points above = vertical;
  for (auto& p : above) p.z += 0.51;
  CHECK(pair(above).count() == 0);
  // Vertex 0 shared, the rest through the interior: adjacent, never counted.
  const Points through = {{0.5, 0.2, -0.5}, {0.2, 0.5, 0.5}};
  Mesh shared = pair(through, {0, 3, 4});
  CHECK(exact::triangles_intersect(horizontal[0], horizontal[1], horizontal[2], shared.pos[0], shared.pos[3],
                                   shared.pos[4]));
  CHECK(shared.count() == 0);
  // The same triangle with its own copy of the vertex is counted.
  CHECK(pair({horizontal[0], through[0], through[1]}).count() == 1);
  // Coplanar: overlapping, disjoint, touching at a point of the hypotenuse.
  CHECK(pair({{0.2, 0.2, 0}, {1.2, 0.2, 0}, {0.2, 1.2, 0}}).count() == 1);
  CHECK(pair({{0.6, 0.6, 0}, {1.6, 0.6, 0}, {0.6, 1.6, 0}}).count() == 0);
  CHECK(pair({{0.5, 0.5, 0}, {1.0, 1.0, 0}, {0.5, 1.5, 0}}).count() == 1);
  CHECK(pair({{0.5, 0.50001, 0}, {1.0, 1.0, 0}, {0.5, 1.5, 0}}).count() == 0);
  // One triangle inside the other, and a tilted coplanar pair (projected on a slanted plane).
  CHECK(pair({{0.1, 0.1, 0}, {0.3, 0.1, 0}, {0.1, 0.3, 0}}).count() == 1);
  auto tilt = [](glm::dvec3 p) { return glm::dvec3(p.x, p.y * 0.6, p.y * 0.8 + 0.25 * p.x); };
  Mesh tilted = pair({{0.2, 0.2, 0}, {1.2, 0.2, 0}, {0.2, 1.2, 0}});
  for (auto& p : tilted.pos) p = tilt(p);
  CHECK(tilted.count() == 1);
  Mesh tilted_apart = pair({{0.6, 0.6, 0}, {1.6, 0.6, 0}, {0.6, 1.6, 0}});
  for (auto& p : tilted_apart.pos) p = tilt(p);
  CHECK(tilted_apart.count() == 0);
  // Touching: a vertex on the other's face, an edge along the other's face, an edge crossing an edge.
  CHECK(pair({{0.3, 0.3, 0}, {0.5, 0.3, 0.5}, {0.3, 0.5, 0.5}}).count() == 1);
  CHECK(pair({{0.3, 0.3, 0}, {0.5, 0.3, 0}, {0.3, 0.5, 0.5}}).count() == 1);
  CHECK(pair({{0.5, -0.5, 0}, {0.5, 0.5, 0}, {0.5, 0, 1}}).count() == 1);
  CHECK(pair({{1.5, -0.5, 0}, {1.5, 0.5, 0}, {1.5, 0, 1}}).count() == 0);
}

TEST_CASE("degenerate and non-finite triangles are skipped, bad indices throw", "[intersections]") {
  Mesh m;
  m.pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -0.5}, {0.2, 0.2, 0.5}, {0.4, 0.3, 0.0}};
  m.tri = {{0, 1, 2}, {3, 4, 5}};
  CHECK(m.count() == 1);
  Mesh nan = m;
  nan.pos[5].x = std::numeric_limits<double>::quiet_NaN();
  CHECK(nan.count() == 0);
  Mesh inf = m;
  inf.pos[1].z = std::numeric_limits<double>::infinity();
  CHECK(inf.count() == 0);
  Mesh collinear = m;
  collinear.pos[5] = {0.2, 0.2, 0.0};  // on the segment from 3 to 4: a needle through the face
  CHECK(collinear.count() == 0);
  Mesh repeated = m;
  repeated.tri[1] = {3, 4, 4};
  CHECK(repeated.count() == 0);
  Mesh bad = m;
  bad.tri[1][2] = 6;
  CHECK_THROWS_AS(bad.count(), std::invalid_argument);
  CHECK(count_self_intersections(Tris{}, Points{}) == 0);
}

TEST_CASE("two grids pushed through each other: the hashed count is the segment brute force's", "[intersections]") {
  // A flat 9 x 9 grid (8 x 8 cells) and a tilted one crossing it along a line, placed at
  // generic offsets so no vertex lies on the other sheet's plane.
  Mesh m = grid(9, 9, [](int x, int y) { return glm::dvec3(x / 8.0, y / 8.0, 0.0); });
  m.append(grid(9, 9, [](int x, int y) {
    const double u = x / 8.0, v = y / 8.0;
    return glm::dvec3(0.0313 + 0.91 * u + 0.0071 * v, 0.0173 + 0.93 * v, 0.6 * (v - 0.4711) + 0.0037 * u);
  }));
  const size_t expected = brute_force_segments(m);
  WARN("two 9x9 grids crossing: " << expected << " intersecting pairs");
  CHECK(expected > 0);
  CHECK(m.count() == expected);
  CHECK(brute_force(m) == expected);
}

TEST_CASE("random triangle soups and a crumpled sheet: the hashed count is the O(n^2) count", "[intersections]") {
  Rng r(20240611);
  // A soup of 300 small triangles in a unit box, some sharing vertices, plus a few large ones
  // (more than 64 cells of the hash: the large list).
  Mesh soup;
  for (int t = 0; t < 300; ++t) {
    const glm::dvec3 c(r.uniform(), r.uniform(), r.uniform());
    const double size = t % 40 == 7 ? 1.5 : 0.08;
    std::array<uint32_t, 3> idx{};
    for (int k = 0; k < 3; ++k) {
      if (k > 0 && t > 10 && r.below(8) == 0) {
        idx[k] = uint32_t(r.below(int(soup.pos.size())));  // a vertex of some earlier triangle
      } else {
        idx[k] = uint32_t(soup.pos.size());
        soup.pos.push_back(c + size * glm::dvec3(r.in(-1, 1), r.in(-1, 1), r.in(-1, 1)));
      }
    }
    soup.tri.push_back(idx);
  }
  const size_t n = brute_force(soup);
  WARN("soup of 300: " << n << " intersecting pairs");
  CHECK(n > 20);
  CHECK(soup.count() == n);
  CHECK(brute_force_segments(soup) == n);  // random doubles: generic, the plain test agrees

  // Two triangles far larger than the cells (the large list) slicing through a rippled grid and
  // each other.
  Mesh sliced = grid(33, 17, [](int x, int y) { return glm::dvec3(x * 0.03, 0.01 * std::sin(x + 2.0 * y), y * 0.03); });
  const auto base = uint32_t(sliced.pos.size());
  sliced.pos.insert(sliced.pos.end(), {{-0.1, -0.2, 0.1}, {1.1, 0.3, 0.2}, {0.4, 0.25, 0.45},
                                       {0.2, 0.3, -0.1}, {0.5, -0.3, 0.6}, {0.9, 0.2, 0.3}});
  sliced.tri.push_back({base, base + 1, base + 2});
  sliced.tri.push_back({base + 3, base + 4, base + 5});
  const size_t s = brute_force(sliced);
  WARN("two large triangles through a 33x17 grid: " << s << " intersecting pairs");
  CHECK(s > 30);
  CHECK(sliced.count() == s);

  // A 20 x 20 sheet crumpled by random offsets as large as its spacing.
  Mesh crumpled = grid(20, 20, [&](int x, int y) {
    return glm::dvec3(x * 0.05, y * 0.05, 0.0) + 0.05 * glm::dvec3(r.in(-1, 1), r.in(-1, 1), r.in(-1, 1));
  });
  const size_t c = brute_force(crumpled);
  WARN("crumpled 20x20: " << c << " intersecting pairs");
  CHECK(c > 20);
  CHECK(crumpled.count() == c);
}

TEST_CASE("a real cloth at rest has no self-intersections", "[intersections]") {
  for (int orientation : {0, 1}) {
    const Scene scene = test::make_scene(15, 15, orientation);
    const ClothModel model = build_cloth(scene);
    CpuBackend<double> backend(scene, model);  // zero frames run
    const ClothSnapshot snap = backend.snapshot();
    CHECK(model.triangles.size() == 14 * 14 * 2);
    CHECK(count_self_intersections(model, snap) == 0);
    ClothSnapshot short_snap = snap;
    short_snap.pos.pop_back();
    CHECK_THROWS_AS(count_self_intersections(model, short_snap), std::invalid_argument);
  }
}

TEST_CASE("a 256 x 256 grid is counted well under a second", "[intersections]") {
  const double s = 1.0 / 255;
  const Mesh flat = grid(256, 256, [&](int x, int y) { return glm::dvec3(x * s, 0.5, y * s); });
  // Rippled, with a far second copy pushed through itself: a fold across the whole sheet.
  Mesh wavy = grid(256, 256, [&](int x, int y) {
    return glm::dvec3(x * s, 0.05 * std::sin(x * 0.07) * std::cos(y * 0.05), y * s);
  });
  Mesh pierced = wavy;
  pierced.append(grid(256, 256, [&](int x, int y) { return glm::dvec3(x * s + 0.3 * s, 0.25 - y * s * 0.5, y * s * 0.866 + 0.1 * s); }));
  auto timed = [](const Mesh& m, size_t& n) {
    const auto t0 = std::chrono::steady_clock::now();
    n = m.count();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  size_t n_flat = 1, n_wavy = 1, n_pierced = 0;
  const double t_flat = timed(flat, n_flat), t_wavy = timed(wavy, n_wavy), t_pierced = timed(pierced, n_pierced);
  WARN(fmt::format("256x256 grid ({} triangles): flat {:.1f} ms, rippled {:.1f} ms; two sheets ({} triangles, {} "
                   "crossing pairs) {:.1f} ms",
                   flat.tri.size(), 1e3 * t_flat, 1e3 * t_wavy, pierced.tri.size(), n_pierced, 1e3 * t_pierced));
  CHECK(n_flat == 0);
  CHECK(n_wavy == 0);
  CHECK(n_pierced > 255);
  CHECK(t_flat < 5.0);  // loose: sanitizer and debug builds too; an O(n^2) search takes minutes
  CHECK(t_wavy < 5.0);
}

TEST_CASE("a million triangles (timing only)", "[.][intersections][timing]") {
  const int n = 708;  // 707^2 * 2 = 999,698 triangles
  const double s = 1.0 / (n - 1);
  const Mesh m = grid(n, n, [&](int x, int y) {
    return glm::dvec3(x * s, 0.05 * std::sin(x * 0.03) * std::cos(y * 0.02), y * s);
  });
  const auto t0 = std::chrono::steady_clock::now();
  const size_t c = m.count();
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  WARN(fmt::format("{} triangles: {} self-intersections in {:.3f} s", m.tri.size(), c, t));
  CHECK(c == 0);
}

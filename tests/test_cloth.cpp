// Cloth construction (DESIGN.md §1): counts, rest lengths, masses, orientations, colours.
#include <catch2/catch.hpp>

#include <set>

#include "cloth.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {
int count_springs(const ClothModel& m, SpringType type) {
  int n = 0;
  for (int i = 0; i < m.count(); ++i)
    for (int d = 0; d < NUM_DIRECTIONS; ++d)
      if (m.rest[i][d] > 0 && kDirections[d].type == type) ++n;
  return n;
}
}  // namespace

TEST_CASE("a 50x50 cloth has 4900 structural, 4802 shearing and 4800 bending springs", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(50, 50, 0).cloth);
  CHECK(count_springs(m, SpringType::Structural) == 4900);
  CHECK(count_springs(m, SpringType::Shearing) == 4802);
  CHECK(count_springs(m, SpringType::Bending) == 4800);
  CHECK(m.springs() == 14502);
  CHECK(m.structural_springs() == 4900);
  CHECK(m.shearing_springs() == 4802);
  CHECK(m.bending_springs() == 4800);
}

TEST_CASE("spring counts on an odd 7x5 grid follow the formulas", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 1).cloth);
  CHECK(count_springs(m, SpringType::Structural) == 6 * 5 + 7 * 4);
  CHECK(count_springs(m, SpringType::Shearing) == 2 * 6 * 4);
  CHECK(count_springs(m, SpringType::Bending) == 5 * 5 + 7 * 3);
}

TEST_CASE("rest lengths are the initial distances", "[cloth]") {
  Scene s = test::make_scene(5, 3, 0, {"cloth.width=2.0", "cloth.height=1.0"});
  ClothModel m = build_cloth(s.cloth);
  const double sx = 2.0 / 4, sy = 1.0 / 2;
  const auto& r = m.rest[m.index(1, 0)];
  CHECK(r[DIR_RIGHT] == Approx(sx));
  CHECK(r[DIR_DOWN] == Approx(sy));
  CHECK(r[DIR_DIAG_DOWN_RIGHT] == Approx(std::hypot(sx, sy)));
  CHECK(r[DIR_DIAG_DOWN_LEFT] == Approx(std::hypot(sx, sy)));
  CHECK(r[DIR_RIGHT2] == Approx(2 * sx));
  CHECK(r[DIR_DOWN2] == Approx(2 * sy));
  // Springs that would leave the grid do not exist.
  CHECK(m.rest[m.index(4, 0)][DIR_RIGHT] == 0);
  CHECK(m.rest[m.index(0, 2)][DIR_DOWN] == 0);
  CHECK(m.rest[m.index(0, 0)][DIR_DIAG_DOWN_LEFT] == 0);
}

TEST_CASE("every particle has mass width*height*density/count", "[cloth]") {
  Scene s = test::make_scene(7, 5, 0, {"cloth.width=2.0", "cloth.density=3.0"});
  ClothModel m = build_cloth(s.cloth);
  CHECK(m.mass == Approx(2.0 * 1.0 * 3.0 / 35));
}

TEST_CASE("a horizontal cloth lies at y = 1 spanning x and z", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 0).cloth);
  for (auto& p : m.initial) CHECK(p.y == 1.0);
  CHECK(m.initial[m.index(6, 4)] == glm::dvec3(1.0, 1.0, 1.0));
  CHECK(m.initial[m.index(3, 2)].x == Approx(0.5));
  CHECK(m.initial[m.index(3, 2)].z == Approx(0.5));
}

TEST_CASE("a vertical cloth spans x and y with a small seeded z offset", "[cloth]") {
  ClothModel a = build_cloth(test::make_scene(7, 5, 1).cloth);
  ClothModel b = build_cloth(test::make_scene(7, 5, 1).cloth);
  std::set<double> zs;
  for (int i = 0; i < a.count(); ++i) {
    CHECK(std::abs(a.initial[i].z) <= 1e-3);
    CHECK(a.initial[i] == b.initial[i]);
    zs.insert(a.initial[i].z);
  }
  CHECK(zs.size() == size_t(a.count()));  // offsets really vary
  CHECK(a.initial[a.index(6, 4)].x == 1.0);
  CHECK(a.initial[a.index(6, 4)].y == 1.0);
}

TEST_CASE("pinned grid indices are marked pinned", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0],[6,4]]"}).cloth);
  CHECK(m.pinned[m.index(0, 0)] == 1);
  CHECK(m.pinned[m.index(6, 4)] == 1);
  CHECK(std::count(m.pinned.begin(), m.pinned.end(), 1) == 2);
}

TEST_CASE("triangles are (A,C,B) and (B,C,D) per cell with grid uvs", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 0).cloth);
  REQUIRE(m.triangles.size() == size_t(2 * 6 * 4));
  CHECK(m.triangles[0] == std::array<uint32_t, 3>{0, 7, 1});
  CHECK(m.triangles[1] == std::array<uint32_t, 3>{1, 7, 8});
  CHECK(m.uv[m.index(3, 2)] == glm::dvec2(0.5, 0.5));
}

TEST_CASE("no two springs of one colour share a particle", "[cloth]") {
  const int nw = 9, nh = 7;
  for (int colour = 0; colour < NUM_COLOURS; ++colour) {
    std::set<int> used;
    int springs = 0;
    const int dir = colour / 2;
    for (int y = 0; y < nh; ++y)
      for (int x = 0; x < nw; ++x) {
        const Direction& d = kDirections[dir];
        if (spring_colour(dir, x, y) != colour || !in_grid(x + d.dx, y + d.dy, nw, nh)) continue;
        ++springs;
        CHECK(used.insert(y * nw + x).second);
        CHECK(used.insert((y + d.dy) * nw + x + d.dx).second);
      }
    CHECK(springs > 0);
  }
}

TEST_CASE("a colour's span holds exactly the springs of that colour", "[cloth]") {
  // The GPU dispatches span.x.count by span.y.count invocations per colour; every spring of
  // the colour must come up once and nothing else. Small, odd and even sizes, 1 included.
  for (auto [nw, nh] : {std::pair{1, 1}, {2, 3}, {3, 2}, {4, 4}, {5, 6}, {7, 5}, {9, 7}, {33, 17}, {64, 3}}) {
    for (int colour = 0; colour < NUM_COLOURS; ++colour) {
      const int dir = colour / 2;
      const Direction& d = kDirections[dir];
      std::set<std::pair<int, int>> expected, spanned;
      for (int y = 0; y < nh; ++y)
        for (int x = 0; x < nw; ++x)
          if (spring_colour(dir, x, y) == colour && in_grid(x + d.dx, y + d.dy, nw, nh)) expected.insert({x, y});
      const ColourSpan s = colour_span(colour, nw, nh);
      for (int iy = 0; iy < s.y.count; ++iy)
        for (int ix = 0; ix < s.x.count; ++ix) CHECK(spanned.insert({s.x.at(ix), s.y.at(iy)}).second);
      INFO(nw << "x" << nh << " colour " << colour);
      CHECK(spanned == expected);
    }
  }
}

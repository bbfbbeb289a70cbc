// Cloth construction (docs/design.md §1, docs/model.md "The cloth model"): counts, rest lengths,
// masses, orientations, colours and the derived lists of the grid builder.
#include <catch2/catch.hpp>

#include <set>

#include "cloth/cloth.hpp"
#include "cloth/spring_grid.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {
int count_springs(const ClothModel& m, SpringType type) {
  int n = 0;
  for (auto& s : m.springs) n += s.type == type;
  return n;
}

// The rest length of the spring from particle i to j (either way round), or 0 if there is none.
double rest_between(const ClothModel& m, int i, int j) {
  for (auto& s : m.springs)
    if ((int(s.i) == i && int(s.j) == j) || (int(s.i) == j && int(s.j) == i)) return s.rest;
  return 0;
}
}  // namespace

TEST_CASE("a 50x50 cloth has 4900 structural, 4802 shearing and 4800 bending springs", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(50, 50, 0));
  CHECK(count_springs(m, SpringType::Structural) == 4900);
  CHECK(count_springs(m, SpringType::Shearing) == 4802);
  CHECK(count_springs(m, SpringType::Bending) == 4800);
  CHECK(m.springs.size() == 14502);
  CHECK(m.structural_springs() == 4900);
  CHECK(m.shearing_springs() == 4802);
  CHECK(m.bending_springs() == 4800);
}

TEST_CASE("spring counts on an odd 7x5 grid follow the formulas", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 1));
  CHECK(count_springs(m, SpringType::Structural) == 6 * 5 + 7 * 4);
  CHECK(count_springs(m, SpringType::Shearing) == 2 * 6 * 4);
  CHECK(count_springs(m, SpringType::Bending) == 5 * 5 + 7 * 3);
}

TEST_CASE("rest lengths are the initial distances", "[cloth]") {
  Scene s = test::make_scene(5, 3, 0, {"cloth.width=2.0", "cloth.height=1.0"});
  ClothModel m = build_cloth(s);
  const double sx = 2.0 / 4, sy = 1.0 / 2;
  CHECK(rest_between(m, m.index(1, 0), m.index(2, 0)) == Approx(sx));
  CHECK(rest_between(m, m.index(1, 0), m.index(1, 1)) == Approx(sy));
  CHECK(rest_between(m, m.index(1, 0), m.index(2, 1)) == Approx(std::hypot(sx, sy)));
  CHECK(rest_between(m, m.index(1, 0), m.index(0, 1)) == Approx(std::hypot(sx, sy)));
  CHECK(rest_between(m, m.index(1, 0), m.index(3, 0)) == Approx(2 * sx));
  CHECK(rest_between(m, m.index(1, 0), m.index(1, 2)) == Approx(2 * sy));
  // Only neighbours one or two steps apart are joined.
  CHECK(rest_between(m, m.index(0, 0), m.index(3, 0)) == 0);
  CHECK(rest_between(m, m.index(0, 0), m.index(2, 1)) == 0);
}

TEST_CASE("every particle has mass width*height*density/count", "[cloth]") {
  Scene s = test::make_scene(7, 5, 0, {"cloth.width=2.0", "cloth.density=3.0"});
  ClothModel m = build_cloth(s);
  for (double mass : m.mass) CHECK(mass == Approx(2.0 * 1.0 * 3.0 / 35));
}

TEST_CASE("a horizontal cloth lies at y = 1 spanning x and z", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 0));
  for (auto& p : m.initial) CHECK(p.y == 1.0);
  CHECK(m.initial[m.index(6, 4)] == glm::dvec3(1.0, 1.0, 1.0));
  CHECK(m.initial[m.index(3, 2)].x == Approx(0.5));
  CHECK(m.initial[m.index(3, 2)].z == Approx(0.5));
}

TEST_CASE("a vertical cloth spans x and y with a small seeded z offset", "[cloth]") {
  ClothModel a = build_cloth(test::make_scene(7, 5, 1));
  ClothModel b = build_cloth(test::make_scene(7, 5, 1));
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
  ClothModel m = build_cloth(test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0],[6,4]]"}));
  CHECK(m.pinned[m.index(0, 0)] == 1);
  CHECK(m.pinned[m.index(6, 4)] == 1);
  CHECK(std::count(m.pinned.begin(), m.pinned.end(), 1) == 2);
}

TEST_CASE("triangles are (A,C,B) and (B,C,D) per cell with grid uvs", "[cloth]") {
  ClothModel m = build_cloth(test::make_scene(7, 5, 0));
  REQUIRE(m.triangles.size() == size_t(2 * 6 * 4));
  CHECK(m.triangles[0] == std::array<uint32_t, 3>{0, 7, 1});
  CHECK(m.triangles[1] == std::array<uint32_t, 3>{1, 7, 8});
  CHECK(m.uv[m.index(3, 2)] == glm::dvec2(0.5, 0.5));
}

TEST_CASE("no two springs of one colour share a particle, and each colour is of one type", "[cloth]") {
  for (auto [nw, nh] : {std::pair{2, 2}, {2, 3}, {3, 2}, {4, 4}, {7, 5}, {9, 7}, {33, 17}, {64, 3}}) {
    INFO(nw << "x" << nh);
    const ClothModel m = build_cloth(test::make_scene(nw, nh, 0));
    if (nw >= 5 && nh >= 5) CHECK(m.colours() == kGridColours);  // the grid's own twelve
    CHECK(m.colours() <= kGridColours);
    CHECK(m.colour_start.back() == m.springs.size());
    for (int c = 0; c < m.colours(); ++c) {
      std::set<uint32_t> used;
      for (uint32_t k = m.colour_start[c]; k < m.colour_start[c + 1]; ++k) {
        CHECK(used.insert(m.springs[k].i).second);
        CHECK(used.insert(m.springs[k].j).second);
        CHECK(m.springs[k].type == m.colour_type(c));
      }
    }
    // Colours run structural, shearing, bending: a sweep visits them in the classic order.
    for (int c = 1; c < m.colours(); ++c)
      if (m.colour_start[c] < m.colour_start[c + 1]) CHECK(int(m.colour_type(c - 1)) <= int(m.colour_type(c)));
  }
}

TEST_CASE("the grid's gather lists hold each particle's springs in kGatherOrder", "[cloth]") {
  const int nw = 7, nh = 5;
  const ClothModel m = build_cloth(test::make_scene(nw, nh, 0));
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) {
      const int i = m.index(x, y);
      std::vector<int> want;  // the other ends, in the classic order
      for (const SpringRef& ref : kGatherOrder) {
        const Direction& d = kDirections[ref.direction];
        const int x2 = x + ref.sign * d.dx, y2 = y + ref.sign * d.dy;
        if (in_grid(x2, y2, nw, nh)) want.push_back(m.index(x2, y2));
      }
      std::vector<int> got;
      for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
        const Spring& s = m.springs[m.gather[g]];
        CHECK((int(s.i) == i || int(s.j) == i));
        got.push_back(int(s.i) == i ? int(s.j) : int(s.i));
      }
      INFO("particle " << x << "," << y);
      CHECK(got == want);
    }
}

TEST_CASE("the corner lists hold every triangle around a particle, ascending", "[cloth]") {
  const ClothModel m = build_cloth(test::make_scene(7, 5, 0));
  for (int i = 0; i < m.count(); ++i) {
    std::vector<uint32_t> want;
    for (uint32_t t = 0; t < m.triangles.size(); ++t)
      for (uint32_t v : m.triangles[t])
        if (int(v) == i) want.push_back(t);
    CHECK(std::vector<uint32_t>(m.corner_triangles.begin() + m.corner_start[i],
                                m.corner_triangles.begin() + m.corner_start[i + 1]) == want);
  }
}

TEST_CASE("two cloths make one model: parts in order, springs never cross", "[cloth]") {
  Scene s = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0]]"});
  Scene second = test::make_scene(4, 3, 1, {"cloth.ks=123", "cloth.pinned=[[3,2]]"});
  s.extra_cloths.push_back(second.cloth);
  const ClothModel m = build_cloth(s);
  REQUIRE(m.parts.size() == 2);
  CHECK(m.count() == 35 + 12);
  CHECK(!m.is_grid());  // several cloths are no longer one grid
  CHECK(m.parts[1].first == 35);
  CHECK(m.parts[1].nw == 4);
  for (auto& sp : m.springs) CHECK((sp.i < 35) == (sp.j < 35));
  for (auto& sp : m.springs) CHECK(sp.material == (sp.i < 35 ? 0u : 1u));
  CHECK(m.material[40] == 1);
  // The second grid is the same cloth it would be alone (its jitter hashes its own indices).
  const ClothModel alone = build_cloth(second);
  for (int i = 0; i < 12; ++i) CHECK(m.initial[35 + i] == alone.initial[i]);
}

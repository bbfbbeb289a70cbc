// Hashed-grid self-collision of the reference (docs/design.md §1 step 3).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "reference/reference.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {
// A 9x18 grid laid as two 9x9 sheets, the upper `gap` metres above the lower one.
struct TwoSheets {
  Scene scene = test::make_scene(9, 18, 0, {"cloth.height=2.0"});
  ClothModel model = build_cloth(scene);
  Constants<double> c = make_constants<double>(scene, model);
  State<double> s = initial_state<double>(model);
  explicit TwoSheets(double gap) {
    for (int y = 0; y < 18; ++y)
      for (int x = 0; x < 9; ++x) {
        auto& p = s.pos[model.index(x, y)];
        p = glm::dvec4(x / 8.0, y < 9 ? 1.0 : 1.0 + gap, (y % 9) / 8.0 + 1e-3 * (y >= 9), p.w);
      }
    s.disp.assign(s.pos.size(), Vec4<double>(0));  // placed at rest
  }
  std::vector<uint32_t> buckets() const {
    std::vector<uint32_t> b;
    for (auto& p : s.pos)
      b.push_back(hash_cell(cell_coord(p.x, c.inv_cell), cell_coord(p.y, c.inv_cell), cell_coord(p.z, c.inv_cell),
                            s.hash.table_size));
    return b;
  }
};
}  // namespace

TEST_CASE("the hash table is a power of two at least the particle count, and at least 4", "[self_collision]") {
  CHECK(hash_table_size(1) == 4);
  CHECK(hash_table_size(4) == 4);
  CHECK(hash_table_size(5) == 8);
  CHECK(hash_table_size(35) == 64);
  CHECK(hash_table_size(64) == 64);
  CHECK(hash_table_size(65) == 128);
}

TEST_CASE("every particle appears exactly once in cell order, ascending within a bucket", "[self_collision]") {
  TwoSheets t(0.005);
  auto b = t.buckets();
  std::vector<uint32_t> order(b.size());
  std::iota(order.begin(), order.end(), 0u);
  count_cells(b, t.s.hash);
  scan_cells(t.s.hash);
  fill_cells(b, order, t.s.hash);
  sort_cells(t.s.hash);
  auto sorted = t.s.hash.entries;
  std::sort(sorted.begin(), sorted.end());
  CHECK(sorted == order);
  for (uint32_t k = 0; k < t.s.hash.table_size; ++k)
    for (uint32_t e = t.s.hash.start[k]; e < t.s.hash.start[k + 1]; ++e) {
      CHECK(b[t.s.hash.entries[e]] == k);
      if (e > t.s.hash.start[k]) CHECK(t.s.hash.entries[e - 1] < t.s.hash.entries[e]);
    }
}

TEST_CASE("self-collision pushes two overlapping sheets apart", "[self_collision]") {
  TwoSheets t(0.005);
  collide_self(t.c, t.s);
  for (int x = 0; x < 9; ++x)
    for (int y = 0; y < 9; ++y) {
      CHECK(t.s.pos[t.model.index(x, y)].y < 1.0);
      CHECK(t.s.pos[t.model.index(x, y + 9)].y > 1.005);
    }
}

TEST_CASE("self-collision does not touch sheets farther apart than twice the thickness", "[self_collision]") {
  TwoSheets t(0.02);
  auto before = t.s.pos;
  collide_self(t.c, t.s);
  CHECK(t.s.pos == before);
}

TEST_CASE("self-collision does not depend on the order particles are filled into cells", "[self_collision]") {
  TwoSheets a(0.004), b(0.004);
  collide_self(a.c, a.s);
  auto buckets = b.buckets();
  std::vector<uint32_t> order(buckets.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(1234));
  count_cells(buckets, b.s.hash);
  scan_cells(b.s.hash);
  fill_cells(buckets, order, b.s.hash);
  sort_cells(b.s.hash);
  resolve_self_contacts(b.c, b.s);
  CHECK(a.s.pos == b.s.pos);  // bitwise
}

TEST_CASE("the correction is the average push divided by simulation_steps", "[self_collision]") {
  // Two free masses 0.01 apart along x (2 * thickness = 0.019): each moves (0.019 - 0.01) / steps.
  Scene s = test::make_scene(2, 2, 0, {"cloth.width=0.01", "cloth.height=5.0"});
  ClothModel m = build_cloth(s);
  auto c = make_constants<double>(s, m);
  auto st = initial_state<double>(m);
  collide_self(c, st);
  CHECK(st.pos[0].x == Approx(-0.009 / 30));
  CHECK(st.pos[1].x == Approx(0.01 + 0.009 / 30));
}

TEST_CASE("the cell of a NaN, infinite or huge coordinate is defined: clamped to 2^30 cells", "[self_collision]") {
  // A float-to-int conversion past 2^31 (or of NaN) is undefined behaviour; a diverging cloth
  // still builds its hash before the guard stops it.
  const int32_t limit = 1 << 30;
  for (float inv : {1.f, 52.6f}) {
    CHECK(cell_coord(std::nanf(""), inv) == -limit);
    CHECK(cell_coord(INFINITY, inv) == limit);
    CHECK(cell_coord(-INFINITY, inv) == -limit);
    CHECK(cell_coord(3e38f, inv) == limit);
    CHECK(cell_coord(-3e38f, inv) == -limit);
  }
  CHECK(cell_coord(std::nan(""), 1.0) == -limit);
  CHECK(cell_coord(1e300, 1.0) == limit);
  CHECK(cell_coord(0.99f, 1.f) == 0);
  CHECK(cell_coord(-0.01f, 1.f) == -1);
}

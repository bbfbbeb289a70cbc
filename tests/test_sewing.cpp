// cloth.seams (issue 45, item 3; docs/model.md, "Sewing"): panels sewn by springs whose rest
// length shrinks to zero, held within max_stretch of it (a weld once sewn). Closed forms: a panel
// sewn under a pinned one hangs by its seam, welded, the pins carrying both panels' weight
// (self-collision or not); two free panels sewn in zero gravity close no faster than the sewing
// speed allows and keep their momentum zero; and the model's seams, colours and welds, and the
// messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "backend.hpp"
#include "sewing_fixtures.hpp"

using namespace clothsim;

namespace {

std::string scene_error(const std::string& text) { return test::setup_error(text, "sew.json"); }

// Two 3 x 3 grid cloths (0.2 m) in the default pose with `seams` on the first.
std::string two_grids(const std::string& seams, const std::string& solver = "fabric") {
  return fmt::format(R"({{
  "cloth": [{{"width": 0.2, "height": 0.2, "num_width_points": 3, "num_height_points": 3, "thickness": 0.004, "orientation": 0, "pinned": [], "seams": [{}]}},
            {{"width": 0.2, "height": 0.2, "num_width_points": 3, "num_height_points": 3, "thickness": 0.004, "orientation": 0, "pinned": []}}],
  "simulation": {{"solver": "{}"}}
}})",
                     seams, solver);
}

}  // namespace

TEST_CASE("a panel sewn under a pinned one hangs by its seam, welded: the pins carry both panels' weight",
          "[sewing]") {
  const std::string solver = GENERATE("classic", "fabric");
  const bool self_collision = GENERATE(false, true);
  INFO(solver << (self_collision ? " with self-collision" : ""));
  test::TempDir dir("sewing", "hang");
  // ks differ: a seam across two cloths takes the lower (200 N/m) on both ends.
  const Scene s = parse_scene(test::hanging_panels_scene(dir, solver, 400, 200, self_collision), dir / "sew.json");
  const ClothModel m = build_cloth(s);
  REQUIRE(m.seam_springs() == 3);
  CpuBackend<double> cpu(s, m);
  auto pos = [&](uint32_t i) { return glm::dvec3(cpu.state().pos[i]); };
  for (int f = 0; f < 270; ++f) cpu.step_frame();  // 3 s: sewn after 0.1 s, then settled
  // Closed: the stretch limit at a rest length of zero welds each pair (docs/model.md, "Sewing").
  double widest = 0;
  for (const Spring& sp : m.springs)
    if (sp.type == SpringType::Seam) widest = std::max(widest, glm::distance(pos(sp.i), pos(sp.j)));
  // At rest the springs at the pins hold up every free mass, the lower panel's through the
  // seam: the vertical pull on the pinned row is the total free weight M g.
  double pull = 0, weight = 0;
  for (const Spring& sp : m.springs) {
    if (sp.type == SpringType::Seam || m.pinned[sp.i] == m.pinned[sp.j]) continue;
    const uint32_t pin = m.pinned[sp.i] ? sp.i : sp.j, other = pin == sp.i ? sp.j : sp.i;
    const glm::dvec3 e = pos(other) - pos(pin);
    const double k = sp.type == SpringType::Bending ? 0.2 * 400 : 400;
    pull -= k * (glm::length(e) - sp.rest) * e.y / glm::length(e);
  }
  for (int i = 0; i < m.count(); ++i)
    if (!m.pinned[i]) weight += m.mass[i] * 9.8;
  INFO("the pins' pull " << pull << " N against the free weight " << weight << " N; widest gap " << widest * 1e3
                         << " mm");
  // Classic: exact. Multigrid and fabric weld after their implicit solve, whose step lets a pair
  // part by about the load over m / dt^2 (7 um here) before the weld joins it again: the upper
  // panel's bottom row ends each substep that much lower than its springs alone would hold it,
  // which reads as 400 N/m x 3.5 um = 1.4 mN more pull a column (measured: 2.5 %; a panel
  // without a seam balances to 1e-6 on all three).
  CHECK(std::abs(pull - weight) < (solver == std::string("classic") ? 0.01 : 0.04) * weight);
  CHECK(widest < 1e-6);
}

TEST_CASE("two free panels sewn in zero gravity close at the sewing speed and keep their momentum zero", "[sewing]") {
  test::TempDir dir("sewing", "free");
  // Side by side in z = 0, 0.1 m apart: A's right column (x = 0.2) sewn to B's left (x = 0.3).
  const std::string a = test::write_panel(dir, "a", 3, 0.2, 0, 0), b = test::write_panel(dir, "b", 3, 0.2, 0.3, 0);
  const Scene s = parse_scene(fmt::format(R"({{
  "cloth": [{{"mesh": "{}", "density": 0.15, "ks": 300, "damping": 1, "thickness": 0.004,
              "seams": [{{"vertices": [2, 5, 8], "to_cloth": 1, "to_vertices": [0, 3, 6]}}]}},
            {{"mesh": "{}", "density": 0.3, "ks": 100, "damping": 1, "thickness": 0.004}}],
  "simulation": {{"solver": "classic", "gravity": [0, 0, 0], "sewing_speed": 0.5, "self_collision": true}}
}})",
                                          a, b),
                              dir / "sew.json");
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  auto widest_gap = [&] {
    double w = 0;
    for (const Spring& sp : m.springs)
      if (sp.type == SpringType::Seam)
        w = std::max(w, glm::distance(glm::dvec3(cpu.state().pos[sp.i]), glm::dvec3(cpu.state().pos[sp.j])));
    return w;
  };
  // While it closes, the stretch limit holds every gap within 1.1 (d0 - v t), d0 = 0.1 m.
  double worst_over = 0;
  for (int f = 0; f < 9; ++f) {
    cpu.step_frame();  // by 0.1 s the rest length is 0.1 - 0.05
    worst_over = std::max(worst_over, widest_gap() - 1.1 * std::max(0.0, 0.1 - 0.5 * (f + 1) / 90.0));
  }
  CHECK(worst_over < 1e-12);
  const double closing = widest_gap();
  for (int f = 9; f < 90; ++f) cpu.step_frame();  // 1 s
  glm::dvec3 momentum(0.0), scale(0.0);
  for (int i = 0; i < m.count(); ++i) {
    momentum += m.mass[i] * glm::dvec3(cpu.state().disp[i]);
    scale += m.mass[i] * glm::abs(glm::dvec3(cpu.state().disp[i]));
  }
  INFO("gap at 0.1 s " << closing * 1e3 << " mm (rest 50 mm); at 1 s " << widest_gap() * 1e3 << " mm; momentum "
                       << glm::length(momentum) << " of " << glm::length(scale) << " kg m / substep");
  CHECK(closing == Approx(0.05).margin(0.005));
  CHECK(widest_gap() < 1e-3);
  CHECK(glm::length(momentum) <= 1e-12 * glm::length(scale) + 1e-18);
}

TEST_CASE("seams become springs of their own colours, gathered after each particle's own, and welds", "[sewing]") {
  // A grid sewn to itself (x_min to x_max: a tube) and to the second cloth (its y_max row to
  // the other's y_min), so particle 2 (x_max, y = 0) has two seams.
  const Scene s = parse_scene(
      two_grids(R"({"edge": "x_min", "to_edge": "x_max"}, {"edge": "y_min", "to_cloth": 1, "to_edge": "y_max"})"),
      "sew.json");
  const ClothModel m = build_cloth(s);
  REQUIRE(m.seam_springs() == 6);
  std::set<std::pair<uint32_t, uint32_t>> pairs;
  for (const Spring& sp : m.springs)
    if (sp.type == SpringType::Seam) pairs.insert({sp.i, sp.j});
  CHECK(pairs == std::set<std::pair<uint32_t, uint32_t>>{{0, 2}, {3, 5}, {6, 8}, {0, 15}, {1, 16}, {2, 17}});
  // Seams come last, in colours of their own, no two at one particle.
  for (int c = 0; c < m.colours(); ++c) {
    std::set<uint32_t> ends;
    for (uint32_t k = m.colour_start[c]; k < m.colour_start[c + 1]; ++k) {
      CHECK(m.springs[k].type == m.colour_type(c));
      CHECK(ends.insert(m.springs[k].i).second);
      CHECK(ends.insert(m.springs[k].j).second);
    }
  }
  CHECK(m.colour_type(m.colours() - 1) == SpringType::Seam);
  // The grid's own gather order first, its seams after.
  const uint32_t first = m.gather_start[2], last = m.gather_start[3];
  CHECK(m.springs[m.gather[last - 1]].type == SpringType::Seam);
  CHECK(m.springs[m.gather[last - 2]].type == SpringType::Seam);
  CHECK(m.springs[m.gather[first]].type != SpringType::Seam);
  // Welds: 0, 2, 15 and 17 are one (0-2, 0-15, 2-17); 1 and 16; 3 and 5; 6 and 8; 4 alone.
  CHECK(m.weld[2] == 0);
  CHECK(m.weld[15] == 0);
  CHECK(m.weld[17] == 0);
  CHECK(m.weld[16] == 1);
  CHECK(m.weld[5] == 3);
  CHECK(m.weld[4] == 4);
}

TEST_CASE("a seam that is not two equal lists of vertices is refused with the key that says so", "[sewing]") {
  CHECK_THAT(scene_error(two_grids(R"({"vertices": [0, 1], "edge": "x_min", "to_edge": "x_max"})")),
             Catch::Contains("cloth[0].seams[0]") && Catch::Contains("exactly one of `vertices`, `edge` and `box`"));
  CHECK_THAT(scene_error(two_grids(R"({"vertices": [0, 1]})")),
             Catch::Contains("cloth[0].seams[0]") && Catch::Contains("`to_vertices`"));
  CHECK_THAT(scene_error(two_grids(R"({"edge": "left", "to_edge": "x_max"})")),
             Catch::Contains("cloth[0].seams[0].edge") && Catch::Contains("\"left\""));
  CHECK_THAT(scene_error(two_grids(R"({"edge": "x_min", "to_cloth": 2, "to_edge": "x_max"})")),
             Catch::Contains("cloth[0].seams[0].to_cloth") && Catch::Contains("got 2"));
  CHECK_THAT(scene_error(two_grids(R"({"edge": "x_min", "to_edge": "x_max"})", "multigrid")),
             Catch::Contains("simulation.solver") && Catch::Contains("became \"fabric\""));
  CHECK_THAT(scene_error(two_grids(R"({"vertices": [0, 1], "to_vertices": [3]})")),
             Catch::Contains("cloth[0].seams[0]") && Catch::Contains("2 and 1 vertices"));
  CHECK_THAT(scene_error(two_grids(R"({"vertices": [0, 9], "to_vertices": [3, 4]})")),
             Catch::Contains("cloth[0].seams[0].vertices[1]") && Catch::Contains("out of range"));
  CHECK_THAT(scene_error(two_grids(R"({"vertices": [4], "to_vertices": [4]})")),
             Catch::Contains("cloth[0].seams[0]") && Catch::Contains("to itself"));
  CHECK_THAT(scene_error(two_grids(R"({"vertices": [-1], "to_vertices": [4]})")),
             Catch::Contains("cloth[0].seams[0].vertices"));
  CHECK_THAT(scene_error(two_grids(R"({"edge": "x_min", "to_edge": "x_max", "needle": 1})")),
             Catch::Contains("cloth[0].seams[0]") && Catch::Contains("needle"));
}

TEST_CASE("a mesh cloth has no grid edges, and a box side is ordered along the box's longest side", "[sewing]") {
  test::TempDir dir("sewing", "box");
  const std::string a = test::write_panel(dir, "a", 3, 0.2, 0, 0), b = test::write_panel(dir, "b", 3, 0.2, 0.3, 0);
  auto scene = [&](const std::string& seam) {
    return fmt::format(R"({{"cloth": [{{"mesh": "{}", "thickness": 0.004, "seams": [{}]}}, {{"mesh": "{}", "thickness": 0.004}}],
                           "simulation": {{"solver": "fabric"}}}})",
                       a, seam, b);
  };
  CHECK_THAT(test::setup_error(scene(R"({"edge": "x_max", "to_cloth": 1, "to_edge": "x_min"})"), dir / "sew.json"),
             Catch::Contains("cloth[0].seams[0].edge") && Catch::Contains("no grid edges"));
  // A's right column (x = 0.2, top to bottom in the list, bottom to top in the box) to B's left.
  const Scene s = parse_scene(
      scene(R"({"box": {"min": [0.19, -1, -1], "max": [0.21, 1, 1]}, "to_cloth": 1, "to_vertices": [0, 3, 6]})"),
      dir / "sew.json");
  const ClothModel m = build_cloth(s);
  std::set<std::pair<uint32_t, uint32_t>> pairs;
  for (const Spring& sp : m.springs)
    if (sp.type == SpringType::Seam) pairs.insert({sp.i, sp.j});
  CHECK(pairs == std::set<std::pair<uint32_t, uint32_t>>{{2, 9}, {5, 12}, {8, 15}});
}

// cloth.attachments (issue 45, item 4; docs/model.md, "Attachments"): vertices tied to a collider
// by zero-length springs follow it. The closed form: a cloth attached at every vertex to a sphere
// that rises and stops hangs below its anchors by m g / k, the springs between its vertices
// unstretched, on every solver that takes attachments; and the loader's and builder's messages.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "backend.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

// A 5x5 cloth of 0.2 m (every mass 0.2 * 0.2 * 0.15 / 25 = 2.4e-4 kg) attached at every vertex
// (`box` around it all) to a sphere that rises 0.1 m in the first second and then stays.
std::string attached_scene(const std::string& solver, const std::string& attachment) {
  return fmt::format(R"({{
  "cloth": {{"width": 0.2, "height": 0.2, "num_width_points": 5, "num_height_points": 5, "thickness": 0.005,
             "orientation": 0, "pinned": [], "density": 0.15, "ks": 50, "damping": 1,
             "attachments": [{}]}},
  "sphere": {{"origin": [0.1, 0.5, 0.1], "radius": 0.02, "friction": 0,
              "motion": {{"keyframes": [[0, [0.1, 0.5, 0.1]], [1, [0.1, 0.6, 0.1]]]}}}},
  "simulation": {{"solver": "{}", "self_collision": false}}
}})",
                     attachment, solver);
}

std::string scene_error(const std::string& text) { return test::setup_error(text, "attach.json"); }

}  // namespace

TEST_CASE("a cloth attached to a sphere that rises and stops hangs m g / k below where it started plus the rise",
          "[attachments]") {
  const std::string solver = GENERATE("classic", "fabric");
  const double k = 10, mass = 0.2 * 0.2 * 0.15 / 25, g = 9.8;
  const Scene s = parse_scene(
      attached_scene(solver, R"({"collider": "sphere", "box": {"min": [-1, -1, -1], "max": [1, 2, 1]}, "stiffness": 10})"),
      "attach.json");
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < 450; ++f) cpu.step_frame();  // 5 s: the sphere stopped at 1 s
  double worst_lag = 0, worst_xz = 0;
  const double lag = mass * g / k;  // 0.235 mm
  for (size_t i = 0; i < m.initial.size(); ++i) {
    const glm::dvec3 x(cpu.state().pos[i]);
    worst_lag = std::max(worst_lag, std::abs((m.initial[i].y + 0.1 - x.y) - lag));
    worst_xz = std::max({worst_xz, std::abs(x.x - m.initial[i].x), std::abs(x.z - m.initial[i].z)});
  }
  INFO(solver << ": lag m g / k = " << lag * 1e3 << " mm; worst deviation " << worst_lag * 1e3 << " mm, sideways "
              << worst_xz * 1e3 << " mm");
  CHECK(worst_lag < 0.01 * lag);
  CHECK(worst_xz < 1e-6);
}

TEST_CASE("an attachment that names no collider or no vertex is refused with the key that says so", "[attachments]") {
  CHECK_THAT(scene_error(attached_scene("fabric", R"({"collider": "sphere[2]", "vertices": [0]})")),
             Catch::Contains("cloth.attachments[0].collider") && Catch::Contains("sphere[2]"));
  CHECK_THAT(scene_error(attached_scene("fabric", R"({"collider": "mesh", "vertices": [0]})")),
             Catch::Contains("cloth.attachments[0].collider"));
  CHECK_THAT(scene_error(attached_scene("fabric", R"({"collider": "sphere"})")),
             Catch::Contains("cloth.attachments[0]") && Catch::Contains("`vertices` or `box`"));
  CHECK_THAT(scene_error(attached_scene("fabric", R"({"collider": "sphere", "vertices": [3, 25]})")),
             Catch::Contains("cloth.attachments[0].vertices[1]") && Catch::Contains("out of range"));
  CHECK_THAT(scene_error(attached_scene("xpbd", R"({"collider": "sphere", "vertices": [0]})")),
             Catch::Contains("simulation.solver") && Catch::Contains("xpbd") && Catch::Contains("removed"));
  CHECK_THAT(scene_error(attached_scene("fabric", R"({"collider": "sphere", "vertices": [0], "stiffness": -1})")),
             Catch::Contains("cloth.attachments[0].stiffness"));
  CHECK(scene_error(attached_scene("fabric", R"({"collider": "sphere[0]", "vertices": [0, 24]})")) == "(no error)");
}

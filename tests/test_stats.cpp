// What `simulate --stats` reports: the clearances are measured where each collider is at the
// snapshot's simulated time, a keyframed one at its keyframed position (diagnostics.hpp).
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "scene/motion.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

// A still horizontal cloth (no gravity, at y = 1) above a sphere and a plane that both move
// down, away from it, over the first second; their static `origin` / `point` are elsewhere (the
// scene's values, which a keyframed collider does not use). A second, static sphere beside it.
const char* const kMovingAway = R"({
  "cloth": {"width": 1.0, "height": 1.0, "num_width_points": 11, "num_height_points": 11,
            "thickness": 0.0095, "orientation": 0},
  "sphere": [{"origin": [0.5, 0.8, 0.5], "radius": 0.1, "friction": 0.3,
              "motion": {"keyframes": [[0, [0.5, 0.7, 0.5]], [1, [0.5, 0.2, 0.5]]]}},
             {"origin": [2, 1, 0.5], "radius": 0.5, "friction": 0.3}],
  "plane": {"point": [0, 0.95, 0], "normal": [0, 1, 0], "friction": 0.5,
            "motion": {"keyframes": [[0, [0, 0.9, 0]], [1, [0, 0.4, 0]]]}},
  "simulation": {"gravity": [0, 0, 0], "self_collision": false}
})";
constexpr int kFrames = 45;  // 0.5 s at 90 frames/s: the sphere at y = 0.45, the plane at 0.65

double sphere_distance(const ClothSnapshot& s, const glm::dvec3& o, double r) {
  double best = std::numeric_limits<double>::infinity();
  for (auto& p : s.pos) best = std::min(best, glm::length(glm::dvec3(p) - o) - r);
  return best;
}
double plane_distance(const ClothSnapshot& s, const glm::dvec3& point, const glm::dvec3& n) {
  double best = std::numeric_limits<double>::infinity();
  for (auto& p : s.pos) best = std::min(best, glm::dot(glm::dvec3(p) - point, n));
  return best;
}

std::string slurp(const std::string& path) {
  std::stringstream ss;
  ss << std::ifstream(path, std::ios::binary).rdbuf();
  return ss.str();
}

double stat_value(const std::string& out, const std::string& label) {
  std::smatch m;
  const std::regex line(std::regex_replace(label, std::regex(R"([\[\]])"), R"(\$&)") + R"( +(-?[0-9.]+) m)");
  INFO(out);
  REQUIRE(std::regex_search(out, m, line));
  return std::stod(m[1]);
}

}  // namespace

TEST_CASE("stats measure a keyframed collider's clearance where it is at the snapshot's time", "[stats]") {
  const Scene s = parse_scene(kMovingAway, "moving_away.json");
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < kFrames; ++f) cpu.step_frame();
  const ClothSnapshot snap = cpu.snapshot();
  const double t = cpu.time();
  REQUIRE(t == Approx(0.5).margin(1e-9));
  const glm::dvec3 sphere_at = interpolate(s.spheres[0].motion->keyframes, t);
  const glm::dvec3 plane_at = interpolate(s.planes[0].motion->keyframes, t);
  REQUIRE(sphere_at.y == Approx(0.45).margin(1e-9));

  const ClothStats st = measure(s, m, snap, t);
  REQUIRE(st.sphere_clearance.size() == 2);
  REQUIRE(st.plane_clearance.size() == 1);
  // Brute force over every particle, the collider where its keys put it at t.
  CHECK(st.sphere_clearance[0] == Approx(sphere_distance(snap, sphere_at, 0.1)).margin(1e-12));
  CHECK(st.sphere_clearance[0] == Approx(0.55 - 0.1).margin(1e-6));  // the cloth did not move
  CHECK(st.plane_clearance[0] == Approx(plane_distance(snap, plane_at, {0, 1, 0})).margin(1e-12));
  CHECK(st.plane_clearance[0] == Approx(1.0 - 0.65).margin(1e-6));
  // Not where the scene's static value is (0.1 and 0.05 from the cloth), nor where the keys
  // start (0.2 and 0.1).
  CHECK(std::abs(st.sphere_clearance[0] - sphere_distance(snap, s.spheres[0].origin, 0.1)) > 0.3);
  CHECK(std::abs(st.plane_clearance[0] - plane_distance(snap, s.planes[0].point, {0, 1, 0})) > 0.25);
  CHECK(measure(s, m, snap, 0.0).sphere_clearance[0] == Approx(0.2).margin(1e-6));
  // The static sphere is where the scene says, whatever the time.
  CHECK(st.sphere_clearance[1] == Approx(sphere_distance(snap, {2, 1, 0.5}, 0.5)).margin(1e-12));
  CHECK(st.sphere_clearance[1] == measure(s, m, snap, 0.0).sphere_clearance[1]);
}

TEST_CASE("simulate --stats prints the clearances of keyframed colliders at the last frame's time", "[stats][cli]") {
  test::TempDir dir("stats", "moving_away");
  const std::string scene = dir / "moving_away.json";
  std::ofstream(scene) << kMovingAway;
  const std::string log = dir / "out.txt";
  const int status = std::system(
      fmt::format("'{}' simulate '{}' --backend cpu --frames {} --stats >'{}' 2>&1", CLOTHSIM_BINARY, scene, kFrames, log)
          .c_str());
  const std::string out = slurp(log);
  INFO(out);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);

  // The same run in process (the CLI's --backend cpu is this double reference, bit for bit).
  const Scene s = parse_scene(kMovingAway, scene);
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < kFrames; ++f) cpu.step_frame();
  const ClothSnapshot snap = cpu.snapshot();
  const double t = cpu.time();
  const double sphere = sphere_distance(snap, interpolate(s.spheres[0].motion->keyframes, t), 0.1);
  const double plane = plane_distance(snap, interpolate(s.planes[0].motion->keyframes, t), {0, 1, 0});
  CHECK(stat_value(out, "sphere[0] clearance") == Approx(sphere).margin(1e-6));  // printed to 6 decimals
  CHECK(stat_value(out, "sphere[1] clearance") == Approx(sphere_distance(snap, {2, 1, 0.5}, 0.5)).margin(1e-6));
  CHECK(stat_value(out, "plane[0] clearance") == Approx(plane).margin(1e-6));
  CHECK(stat_value(out, "sphere[0] clearance") == Approx(0.45).margin(1e-5));
  CHECK(stat_value(out, "plane[0] clearance") == Approx(0.35).margin(1e-5));
}

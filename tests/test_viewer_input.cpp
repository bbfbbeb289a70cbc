// Viewer input maths without a window: camera orbit/pan/zoom, picking and dragging.
#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "picking.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {
// Pixel of a world point for a camera and viewport (y from the top, as the mouse reports it).
glm::vec2 project(const OrbitCamera& cam, glm::vec3 p, glm::vec2 viewport) {
  glm::vec4 c = cam.view_projection() * glm::vec4(p, 1.f);
  c /= c.w;
  return {(c.x + 1.f) * 0.5f * viewport.x, (1.f - c.y) * 0.5f * viewport.y};
}
}  // namespace

TEST_CASE("orbiting keeps the distance to the target and moves the eye around it", "[viewer]") {
  OrbitCamera cam;
  const glm::vec3 eye0 = cam.eye();
  cam.orbit(100.f, 0.f);
  CHECK(glm::length(cam.eye() - cam.target) == Approx(cam.distance));
  CHECK(glm::length(cam.eye() - eye0) > 0.1f);
  CHECK(cam.eye().y == Approx(eye0.y));  // horizontal drag: same height
  cam.orbit(0.f, 1e6f);
  CHECK(cam.pitch < 1.571f);  // clamped short of the pole
}

TEST_CASE("panning moves target and eye together by the dragged screen distance", "[viewer]") {
  OrbitCamera cam;
  const glm::vec3 t0 = cam.target, e0 = cam.eye();
  const glm::vec2 viewport(800, 600);
  const glm::vec2 before = project(cam, glm::vec3(0.5f, 0.5f, 0.5f), viewport);
  cam.pan(40.f, 0.f, viewport.y);
  CHECK(glm::length((cam.target - t0) - (cam.eye() - e0)) < 1e-5f);
  // The world point under the cursor follows the mouse: 40 px to the right.
  const glm::vec2 after = project(cam, glm::vec3(0.5f, 0.5f, 0.5f), viewport);
  CHECK(after.x - before.x == Approx(40.f).margin(1.0));
  CHECK(after.y == Approx(before.y).margin(1.0));
}

TEST_CASE("zooming in shortens the distance and zooming out restores it", "[viewer]") {
  OrbitCamera cam;
  const float d0 = cam.distance;
  cam.zoom(3.f);
  CHECK(cam.distance < d0);
  cam.zoom(-3.f);
  CHECK(cam.distance == Approx(d0));
}

TEST_CASE("the pick ray through a particle's pixel hits that particle on a known cloth", "[viewer]") {
  Scene s = test::make_scene(9, 7, 0);
  ClothModel m = build_cloth(s);
  std::vector<glm::vec4> pos;
  for (auto& p : m.initial) pos.emplace_back(glm::vec3(p), 1.f);
  OrbitCamera cam = default_camera(s, m, 800.f / 600.f);
  const glm::vec2 viewport(800, 600);
  for (int i : {10, 22, 31, 50}) {  // interior particles: a corner pixel may fall just off the cloth
    const Ray ray = pick_ray(cam, project(cam, glm::vec3(pos[i]), viewport), viewport);
    auto picked = pick_particle(ray, pos, m);
    REQUIRE(picked.has_value());
    CHECK(*picked == i);
  }
  // A ray into empty space picks nothing.
  CHECK_FALSE(pick_particle(pick_ray(cam, {1.f, 1.f}, viewport), pos, m).has_value());
}

TEST_CASE("picking works on a mesh cloth: the ray through a vertex's pixel picks that vertex", "[viewer][mesh]") {
  const Scene s = load_scene(std::string(CLOTHSIM_SOURCE_DIR) + "/scenes/disc_hole.json");
  const ClothModel m = build_cloth(s);
  std::vector<glm::vec4> pos;
  for (auto& p : m.initial) pos.emplace_back(glm::vec3(p), 1.f);
  OrbitCamera cam = default_camera(s, m, 800.f / 600.f);
  const glm::vec2 viewport(800, 600);
  int tried = 0;
  for (int i = 60; i < m.count(); i += 53) {  // inner rings' vertices, away from the rims
    const glm::dvec3 p = m.initial[i];
    const double r = std::hypot(p.x, p.z);
    if (r < 0.22 || r > 0.43) continue;
    ++tried;
    const Ray ray = pick_ray(cam, project(cam, glm::vec3(pos[i]), viewport), viewport);
    auto picked = pick_particle(ray, pos, m);
    REQUIRE(picked.has_value());
    CHECK(*picked == i);
  }
  CHECK(tried >= 3);
  // The hole picks nothing: a ray through the disc's centre.
  CHECK_FALSE(pick_particle(pick_ray(cam, project(cam, glm::vec3(0, 1, 0), viewport), viewport), pos, m).has_value());
}

TEST_CASE("a grabbed particle follows the mouse in the plane facing the camera", "[viewer]") {
  OrbitCamera cam;
  const glm::vec3 grabbed(0.5f, 1.f, 0.5f);
  const Grab g = begin_grab(7, grabbed, cam);
  const glm::vec2 viewport(800, 600);
  const glm::vec2 px = project(cam, grabbed, viewport);
  // No mouse motion: the particle stays where it was grabbed.
  CHECK(glm::length(g.target(pick_ray(cam, px, viewport)) - grabbed) < 1e-4f);
  // Moving the mouse moves it within the plane, and it stays under the cursor.
  const glm::vec3 moved = g.target(pick_ray(cam, px + glm::vec2(50, -30), viewport));
  CHECK(glm::dot(moved - grabbed, g.plane_normal) == Approx(0.f).margin(1e-5));
  const glm::vec2 moved_px = project(cam, moved, viewport);
  CHECK(moved_px.x == Approx(px.x + 50).margin(0.5));
  CHECK(moved_px.y == Approx(px.y - 30).margin(0.5));
}

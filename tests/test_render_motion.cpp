// Moving colliders as drawn: the renderer builds each collider's mesh once, where the scene
// file puts it, and translates it to where the simulation has it now (Renderer::place_colliders,
// from the simulator's constants before every draw), so a keyframed sphere or mesh is drawn moving.
#include <glad/gl.h>

#include <cmath>

#include <glm/vec2.hpp>

#include "render_stage.hpp"

using namespace clothsim;
using namespace clothsim::test;

TEST_CASE("a keyframed sphere is drawn where the simulation has it at a later frame", "[gpu][render]") {
  REQUIRE_GL_CONTEXT();
  // Weightless, the flat cloth stays at y = 1, nearly edge-on from this camera and well above
  // the sphere, which crosses 0.6 m along -x in its first 0.1 s (9 frames) and then stays.
  StageOptions o;
  o.sets = {"simulation.gravity=[0,0,0]",
            R"(sphere.motion={"keyframes": [[0, [0.5, 0.2, 0.5]], [0.1, [-0.1, 0.2, 0.5]]]})"};
  Stage stage("sphere", kWidth, kHeight, o);
  stage.camera.look_from({0.2f, 0.2f, 2.5f}, {0.2f, 0.2f, 0.5f});

  stage.run(1);
  const glm::vec3 start = glm::vec3(stage.gpu.constants().control.spheres[0].origin_radius);
  const Image before = stage.draw(ShaderKind::Diffuse);
  stage.run(17);  // frame 18, 0.2 s: past the last key
  const glm::vec3 now = glm::vec3(stage.gpu.constants().control.spheres[0].origin_radius);
  REQUIRE(now.x == Approx(-0.1f));
  REQUIRE(start.x > 0.4f);  // 1/90 s in, it has moved 0.067 m of its 0.6 m
  const Image after = stage.draw(ShaderKind::Diffuse);

  const glm::ivec2 from(stage.pixel_of(start)), to(stage.pixel_of(now));
  INFO("sphere centre from pixel (" << from.x << ", " << from.y << ") to (" << to.x << ", " << to.y << ")");
  REQUIRE(before.inside(from.x, from.y));
  REQUIRE(after.inside(to.x, to.y));
  // Where it was: sphere, then background; where it went: background, then sphere. A renderer
  // drawing the scene's static origin would fail the second and fourth checks.
  CHECK_FALSE(is_background(before.at(from.x, from.y)));
  CHECK(is_background(after.at(from.x, from.y)));
  CHECK(is_background(before.at(to.x, to.y)));
  CHECK_FALSE(is_background(after.at(to.x, to.y)));
  // And the whole sphere moved: about as many sphere pixels as before, now around `to`.
  int near_to = 0, near_from = 0;
  const int r = int(std::abs(float(to.x - from.x)) / 3.f);
  for (int y = 0; y < after.h; ++y)
    for (int x = 0; x < after.w; ++x) {
      if (is_background(after.at(x, y))) continue;
      near_to += (x - to.x) * (x - to.x) + (y - to.y) * (y - to.y) < r * r;
      near_from += (x - from.x) * (x - from.x) + (y - from.y) * (y - from.y) < r * r;
    }
  CHECK(near_to > 0);
  CHECK(near_from == 0);
}

TEST_CASE("a mesh collider is drawn, with every shader, and moves where its keyframes put it", "[gpu][render][long]") {
  REQUIRE_GL_CONTEXT();
  // flag_pole's pole (meshes/pole.obj), keyframed 0.5 m along -x over its first 0.1 s; the
  // flag is weightless and windless, so it stays in its plane at x >= 0, and the camera looks
  // along -z at the pole's middle.
  StageOptions o;
  o.sets = {"simulation.gravity=[0,0,0]", "wind.velocity=[0,0,0]",
            R"(mesh.motion={"keyframes": [[0, [-0.03, 0.12, 0]], [0.1, [-0.53, 0.12, 0]]]})"};
  Stage stage("flag_pole", kWidth, kHeight, o);
  stage.camera.look_from({-0.3f, 0.3f, 2.0f}, {-0.3f, 0.3f, 0.f});
  const glm::ivec2 at(stage.pixel_of({-0.03f, 0.3f, 0.f})), later(stage.pixel_of({-0.53f, 0.3f, 0.f}));
  REQUIRE(stage.gpu.constants().control.meshes.size() == 1);
  for (int k = 0; k < 8; ++k) {
    INFO(kShaderNames[size_t(k)]);
    Appearance look = Appearance::classic();
    look.shader = ShaderKind(k);
    const Image shown = stage.draw(look);
    look.show_meshes = false;
    const Image hidden = stage.draw(look);
    REQUIRE(shown.inside(at.x, at.y));
    if (look.shader != ShaderKind::Wireframe) CHECK_FALSE(is_background(shown.at(at.x, at.y)));
    CHECK(is_background(hidden.at(at.x, at.y)));
    CHECK(count_foreground(shown) > count_foreground(hidden));
  }
  stage.run(18);  // 0.2 s: past the last key
  const Image moved = stage.draw(ShaderKind::Diffuse);
  CHECK(is_background(moved.at(at.x, at.y)));
  CHECK_FALSE(is_background(moved.at(later.x, later.y)));
}

// The demo look (docs/rendering.md), measured in pictures: the key light's shadow on the floor
// (dark where the geometry says, gone with shadows off, soft far from its caster and tight at
// contact), no acne on a draped cloth, ambient occlusion at contact, a shadow map fitted to
// the scene, the back tint, and the studio floor under a scene without a plane.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "render_stage.hpp"

using namespace clothsim;
using namespace clothsim::test;

namespace {

double grey(const uint8_t* p) { return (double(p[0]) + double(p[1]) + double(p[2])) / 3.0; }

// The plane scene's cloth cut to 30 x 30 cm (7 x 5 masses), flat at y = 1 where it starts
// and drawn there (nothing is simulated), over its floor `gap` metres below, seen from 60 cm
// above and a little towards -z, where the key light (above, +x, +z) throws its shadow.
constexpr int kLookW = 800, kLookH = 600;
constexpr float kCloth = 0.3f;
struct FloorStage {
  float gap;
  Stage stage;
  explicit FloorStage(float g)
      : gap(g), stage("plane", kLookW, kLookH,
                      {.sets = {"cloth.width=0.3", "cloth.height=0.3", "cloth.num_width_points=7",
                                "cloth.num_height_points=5", "plane.point=[0," + std::to_string(1.0 - double(g)) + ",0]"}}) {
    stage.camera.look_from({0.15f, 1.6f, 0.03f}, {0.15f, 1.f, 0.15f});
  }
  float floor_y() const { return 1.f - gap; }
  glm::vec3 light() const { return stage.renderer.light_position(stage.camera, Appearance{}); }
  // The floor's shadow of the cloth's -z edge (z = 0), by similar triangles from the light.
  float shadow_edge_z() const {
    const glm::vec3 l = light();
    return l.z + (0.f - l.z) * (l.y - floor_y()) / (l.y - 1.f);
  }
  // Mean grey of the floor pixels whose floor point lies at z in [z0, z1] (x within the
  // cloth's middle 60 %), skipping pixels whose ray meets the cloth (or comes within 2 mm of it).
  double floor_mean(const Image& im, float z0, float z1) const {
    const auto [mean, n] = floor_stats(im, z0, z1);
    INFO("floor pixels with z in [" << z0 << ", " << z1 << "]: " << n);
    REQUIRE(n >= 40);
    return mean;
  }
  std::pair<double, int> floor_stats(const Image& im, float z0, float z1) const {
    const glm::mat4 inverse = glm::inverse(stage.camera.view_projection());
    double sum = 0;
    int n = 0;
    for (int y = 0; y < im.h; ++y)
      for (int x = 0; x < im.w; ++x) {
        const glm::vec2 ndc((float(x) + 0.5f) / float(im.w) * 2.f - 1.f, 1.f - (float(y) + 0.5f) / float(im.h) * 2.f);
        glm::vec4 a = inverse * glm::vec4(ndc, -1.f, 1.f), b = inverse * glm::vec4(ndc, 1.f, 1.f);
        const glm::vec3 o = glm::vec3(a) / a.w, d = glm::vec3(b) / b.w - o;
        const glm::vec3 on_cloth = o + d * ((1.f - o.y) / d.y), on_floor = o + d * ((floor_y() - o.y) / d.y);
        const float m = 0.002f;
        if (on_cloth.x > -m && on_cloth.x < kCloth + m && on_cloth.z > -m && on_cloth.z < kCloth + m) continue;
        if (on_floor.x < 0.2f * kCloth || on_floor.x > 0.8f * kCloth || on_floor.z < z0 || on_floor.z > z1) continue;
        sum += grey(im.at(x, y));
        ++n;
      }
    return {n > 0 ? sum / n : 0.0, n};
  }
  Image draw(bool shadows, bool occlusion = true) {
    Appearance look;  // the demo look: studio, shadows, occlusion
    look.shadows = shadows;
    look.ambient_occlusion = occlusion;
    return stage.draw(look);
  }
};

// Where the floor's grey, going away from the cloth's -z edge, rises from its darkest to
// `lit` (the mean at `to`): the distances (m) at which it passes 20 % and 80 % of the way,
// from a profile of floor pixels in 0.5 mm steps (a step no pixel falls in is skipped).
std::pair<float, float> rise(const FloorStage& s, const Image& im, float from, float to) {
  std::vector<std::pair<float, double>> profile;
  for (float d = from; d < to; d += 0.0005f) {
    const auto [mean, n] = s.floor_stats(im, -d - 0.0005f, -d);
    if (n > 0) profile.push_back({d, mean});
  }
  REQUIRE(profile.size() > 10);
  auto darkest = std::min_element(profile.begin(), profile.end(), [](auto& a, auto& b) { return a.second < b.second; });
  const double dark = darkest->second, lit = profile.back().second;
  float at20 = -1, at80 = -1;
  for (auto k = darkest; k != profile.end(); ++k) {
    const double share = (k->second - dark) / std::max(lit - dark, 1e-9);
    if (at20 < 0 && share >= 0.2) at20 = k->first;
    if (at80 < 0 && share >= 0.8) at80 = k->first;
  }
  return {at20, at80};
}

}  // namespace

TEST_CASE("the cloth's shadow on the floor 5 cm below is over 35 % darker, and within 2 % with shadows off",
          "[gpu][render][look][long]") {
  REQUIRE_GL_CONTEXT();
  FloorStage s(0.05f);
  const float edge = s.shadow_edge_z();  // about -3.4 cm: the shadow reaches past the cloth's edge
  INFO("the shadow of the cloth's -z edge lies at z = " << edge);
  REQUIRE(edge < -0.025f);
  // Inside the shadow by at least a centimetre (its penumbra is about 5 mm wide each side),
  // and lit floor just beyond it, on the same strip of floor.
  for (bool shadows : {true, false}) {
    const Image im = s.draw(shadows);
    const double inside = s.floor_mean(im, edge + 0.01f, -0.004f), outside = s.floor_mean(im, edge - 0.022f, edge - 0.01f);
    INFO("shadows " << (shadows ? "on" : "off") << ": floor grey " << inside << " in the shadow, " << outside << " beside it");
    if (shadows) CHECK(inside <= 0.65 * outside);
    else CHECK(std::abs(inside / outside - 1.0) <= 0.02);
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a cloth 0.5 mm above the floor casts its shadow at its edge, farther up a detached one, softer the farther",
          "[gpu][render][look][long]") {
  REQUIRE_GL_CONTEXT();
  FloorStage touching(0.0005f), low(0.01f), apart(0.05f);
  const Image touching_image = touching.draw(true), apart_image = apart.draw(true);
  // Touching: the shadow ends where the cloth does (0.3 mm beyond its edge, hidden by it): the
  // floor is lit from 3 mm past the edge on. 5 cm up, the floor there is still in the shadow,
  // which the light's slant has moved 3 cm away from the cloth's outline.
  const double touching_lit = touching.floor_mean(touching_image, -0.06f, -0.05f);
  const double touching_edge = touching.floor_mean(touching_image, -0.008f, -0.003f);
  const double apart_lit = apart.floor_mean(apart_image, -0.08f, -0.07f);
  const double apart_edge = apart.floor_mean(apart_image, -0.008f, -0.003f);
  INFO("3-8 mm past the edge: " << touching_edge << " (0.5 mm gap, lit " << touching_lit << "), " << apart_edge
                                << " (5 cm gap, lit " << apart_lit << ")");
  CHECK(touching_edge >= 0.97 * touching_lit);
  CHECK(apart_edge <= 0.65 * apart_lit);
  // The edge's sharpness: over how far the floor rises from 20 % to 80 % lit, with the cloth
  // 1 cm up (the shadow 6 mm past its edge) and 5 cm up (3.4 cm past it).
  // The shadow's own edge: occlusion off (within its reach of the 1 cm gap it would soften it).
  const auto [low20, low80] = rise(low, low.draw(true, false), 0.002f, 0.03f);
  const auto [apart20, apart80] = rise(apart, apart.draw(true, false), 0.02f, 0.07f);
  INFO("rise from 20 to 80 % lit: " << (low80 - low20) * 1000 << " mm (1 cm gap, at " << low20 * 1000 << " mm), "
                                    << (apart80 - apart20) * 1000 << " mm (5 cm gap, at " << apart20 * 1000 << " mm)");
  REQUIRE(low20 >= 0);
  REQUIRE(apart20 >= 0);
  CHECK((low80 - low20) < 0.5f * (apart80 - apart20));
  CHECK(low20 < 0.012f);       // the 1 cm gap's shadow ends within about 6 mm of the outline
  CHECK(apart20 > 0.025f);     // the 5 cm gap's some 3.4 cm away
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("shadows put no pixel-scale acne on the lit side of a cloth draped over the sphere", "[gpu][render][look][long]") {
  REQUIRE_GL_CONTEXT();
  Stage stage("sphere", 320, 240);
  stage.run(100);
  stage.camera.look_from({1.1f, 0.6f, 1.4f}, {0.5f, 0.05f, 0.5f});
  // The lit side: cloth pixels whose 3x3 neighbourhood is all cloth, facing the light
  // (normals from the Normal shader, which draws only the cloth over the background here).
  Appearance normal = Appearance::classic(ShaderKind::Normal);
  normal.show_spheres = false;
  const Image normals = stage.draw(normal);
  const glm::vec3 l = glm::normalize(stage.renderer.light_position(stage.camera, Appearance{}) - glm::vec3(0.5f, 0.3f, 0.5f));
  std::vector<glm::ivec2> lit;
  for (int y = 1; y + 1 < normals.h; ++y)
    for (int x = 1; x + 1 < normals.w; ++x) {
      bool inside = true;
      for (int j = -1; j <= 1 && inside; ++j)
        for (int i = -1; i <= 1 && inside; ++i) inside = !is_background(normals.at(x + i, y + j));
      const uint8_t* c = normals.at(x, y);
      const glm::vec3 n(c[0] / 127.5f - 1.f, c[1] / 127.5f - 1.f, c[2] / 127.5f - 1.f);
      if (inside && glm::dot(n, l) > 0.3f) lit.push_back({x, y});
    }
  INFO(lit.size() << " lit cloth pixels");
  REQUIRE(lit.size() > 2000);
  auto roughness = [&](bool shadows) {
    Appearance look;
    look.shadows = shadows;
    look.ambient_occlusion = false;
    const Image im = stage.draw(look);
    double sum = 0;
    for (const glm::ivec2& p : lit) {
      double mean = 0;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) mean += grey(im.at(p.x + i, p.y + j)) / 9.0;
      sum += std::pow(grey(im.at(p.x, p.y)) - mean, 2);
    }
    return std::sqrt(sum / double(lit.size()));
  };
  const double with = roughness(true), without = roughness(false);
  INFO("RMS of pixel minus its 3x3 mean over the lit cloth: " << with << " with shadows, " << without << " without");
  CHECK(with <= 1.2 * without);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("ambient occlusion darkens the creases of a cloth draped over the sphere, not its smooth top",
          "[gpu][render][look][long]") {
  REQUIRE_GL_CONTEXT();
  Stage stage("sphere", 320, 240);
  stage.run(100);
  stage.camera.look_from({1.1f, 0.6f, 1.4f}, {0.5f, 0.05f, 0.5f});
  Appearance look;
  look.shadows = false;
  const Image with = stage.draw(look);
  look.ambient_occlusion = false;
  const Image without = stage.draw(look);
  // Cloth pixels: where the classic look (flat background) does not show the background.
  Appearance plain = Appearance::classic(ShaderKind::Phong);
  plain.show_spheres = false;
  const Image mask = stage.draw(plain);
  const glm::vec2 top = stage.pixel_of(glm::vec3(stage.scene.spheres[0].origin) +
                                       glm::vec3(0.f, float(stage.scene.spheres[0].radius) + 0.01f, 0.f));
  int cloth = 0, darkened = 0, at_top = 0;
  double top_with = 0, top_without = 0;
  for (int y = 0; y < with.h; ++y)
    for (int x = 0; x < with.w; ++x) {
      if (is_background(mask.at(x, y))) continue;
      ++cloth;
      darkened += grey(with.at(x, y)) < 0.9 * grey(without.at(x, y));
      if (glm::length(glm::vec2(x, y) + 0.5f - top) < 6.f) {
        top_with += grey(with.at(x, y)), top_without += grey(without.at(x, y));
        ++at_top;
      }
    }
  INFO(cloth << " cloth pixels, " << darkened << " darkened by over 10 %; " << at_top << " on the top: "
             << top_with / at_top << " with occlusion, " << top_without / at_top << " without");
  REQUIRE(at_top > 30);
  CHECK(darkened > cloth / 50);
  CHECK(darkened < cloth / 2);
  CHECK(std::abs(top_with / top_without - 1.0) <= 0.02);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the shadow map is fitted to the cloth: as many texels across a 20 cm napkin as a 2 m curtain",
          "[gpu][render][look]") {
  REQUIRE_GL_CONTEXT();
  auto texels_across = [](double size) {
    const std::string side = std::to_string(size);
    Stage stage("sphere", 160, 120, {.sets = {"cloth.width=" + side, "cloth.height=" + side, "cloth.num_width_points=7",
                                              "cloth.num_height_points=5", "sphere.origin=[0,-10,0]"}});
    Appearance look;
    look.show_spheres = false;  // the sphere is far below: only the cloth casts
    stage.draw(look);
    const layout::ShadowFrame f = stage.renderer.shadow_map()->frame();
    // The map's width at the cloth's distance along the axis, over the cloth's side.
    const double depth = 0.5 * (f.range.x + f.range.y);
    return size / (2.0 * f.range.z * depth * f.range.w);
  };
  const double napkin = texels_across(0.2), curtain = texels_across(2.0);
  INFO("texels across the cloth: " << napkin << " (20 cm), " << curtain << " (2 m)");
  CHECK(napkin > 1000);
  CHECK(std::abs(napkin / curtain - 1.0) < 0.05);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the back tint colours only the cloth's back, and the studio floor lies under a scene without a plane",
          "[gpu][render][look]") {
  REQUIRE_GL_CONTEXT();
  Stage stage("sphere", 160, 120);
  Appearance look = Appearance::classic(ShaderKind::Phong);
  look.show_spheres = false;
  auto centre = [&](const Appearance& a) {
    const Image im = stage.draw(a);
    const uint8_t* p = im.at(im.w / 2, im.h / 2);
    return glm::vec3(p[0], p[1], p[2]);
  };
  // The flat cloth from above shows its front, from below its back.
  stage.camera.look_from({0.5f, 2.f, 0.6f}, {0.5f, 1.f, 0.5f});
  const glm::vec3 front = centre(look);
  stage.camera.look_from({0.5f, 0.2f, 0.6f}, {0.5f, 1.f, 0.5f});
  const glm::vec3 back = centre(look);
  look.back_tint = {0.5f, 1.f, 1.f};
  const glm::vec3 back_tinted = centre(look);
  stage.camera.look_from({0.5f, 2.f, 0.6f}, {0.5f, 1.f, 0.5f});
  const glm::vec3 front_tinted = centre(look);
  INFO("front " << front.x << "," << front.y << "; back " << back.x << "," << back.y << " -> " << back_tinted.x << ","
                << back_tinted.y << "; front with the tint " << front_tinted.x);
  CHECK(front_tinted == front);
  CHECK(back_tinted.x < 0.85f * back.x);
  CHECK(std::abs(back_tinted.y - back.y) <= 1.f);

  // No plane in this scene: with `floor`, the studio floor appears below the sphere's bottom.
  Appearance studio;
  studio.ambient_occlusion = false;
  stage.camera.look_from({0.5f, 0.3f, 3.f}, {0.5f, 0.f, 0.5f});
  const Image without = stage.draw(studio);
  studio.floor = true;
  const Image with = stage.draw(studio);
  // Below the sphere's bottom and where the cloth will roughly hang to (camera.hpp's
  // resting_points), so nothing is drawn through it.
  const float bottom = float(stage.scene.spheres[0].origin.y - stage.scene.spheres[0].radius);
  CHECK(stage.renderer.floor_height() < bottom);
  for (const glm::dvec3& p : resting_points(stage.scene, stage.model)) CHECK(stage.renderer.floor_height() < p.y);
  int changed = 0;
  for (int y = with.h * 3 / 4; y < with.h; ++y)
    for (int x = 0; x < with.w; ++x) changed += std::abs(grey(with.at(x, y)) - grey(without.at(x, y))) > 4.0;
  CHECK(changed > with.w * with.h / 8);
  CHECK_NO_GL_ERRORS();
}

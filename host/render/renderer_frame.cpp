// Renderer::draw: a frame of the scene, pass by pass (shadow map, ambient occlusion, the
// colliders and the cloth, the studio floor), timed per pass when asked (PassClock).
#include "renderer.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "camera.hpp"
#include "context.hpp"
#include "renderer_detail.hpp"

namespace clothsim {

void Renderer::draw(const gl::Buffer& positions, const gl::Buffer& normals, const OrbitCamera& camera,
                    const Appearance& look) {
  if (timing_ && !clock_) clock_ = std::make_unique<PassClock<3>>(gl::gl_renderer_is_llvmpipe());
  auto mark = [&](int boundary) {
    if (timing_) clock_->mark(boundary);
  };
  mark(0);
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_MULTISAMPLE);
  const bool lit = is_lit(look.shader);
  const bool shadows = lit && look.shadows, occlusion = lit && look.ambient_occlusion;
  // The key light (Appearance::light, by default above, right of and in front of the target):
  // irradiance 0.8 at the target. Cloth
  // nearer to it gets more, which the tone map rolls off instead of clipping.
  const glm::vec3 eye = camera.eye();
  const glm::vec3 light = light_position(camera, look);
  const float d2 = glm::dot(light - camera.target, light - camera.target);

  // The shadow pass: the casters from the light, into a map fitted to them this frame.
  if (shadows) {
    if (!shadow_) shadow_ = std::make_unique<ShadowMap>(root_ / "shaders", shadow_map_size_);
    const auto [lo, hi] = collider_box(look);
    // A disc of radius a tenth of the light's distance (a studio softbox): contact shadows stay
    // sharp, a cloth's shadow 5 cm below it softens over about a centimetre.
    shadow_->fit(positions, model_.count(), light, 0.1f * std::sqrt(d2), lo, hi);
    shadow_->begin();
    draw_objects(shadow_->caster_program(), positions, normals, look, Pass::Casters);
    shadow_->end();
  }
  mark(1);
  // Ambient occlusion: the depth pre-pass, then the two screen-space passes. Its reach is 6 %
  // of the cloth's size: a fold's depth, and contact within a few centimetres of a 1 m cloth.
  const bool displaced = look.shader == ShaderKind::Displacement;
  if (occlusion) {
    if (!occlusion_) occlusion_ = std::make_unique<AmbientOcclusion>(root_ / "shaders");
    occlusion_->begin_depth();
    gl::Program& depth = depth_program(displaced);
    depth.set("u_view_projection", camera.view_projection());
    if (displaced) {
      depth.set("u_height_texture", 1);
      depth.set("u_height_scaling", look.height_scaling);
      bumps_height_.bind(1);
    }
    draw_objects(depth, positions, normals, look, Pass::Depth);
    occlusion_->compute(camera.projection(), 0.06f * scene_size_);
  }
  mark(2);

  glClearColor(0.16f, 0.17f, 0.2f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl::Program& prog = program(look.shader);
  const glm::vec2 viewport_size{float(viewport[2]), float(viewport[3])};
  if (look.studio) {
    // The background gradient, behind everything: no depth written.
    if (!background_)
      background_ = gl::Program::graphics(root_ / "shaders" / "fullscreen.vert", root_ / "shaders" / "background.frag");
    background_->set("u_viewport", viewport_size);
    glDepthMask(GL_FALSE);
    background_->use();
    empty_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
  }
  prog.set("u_view_projection", camera.view_projection());
  prog.set("u_camera_position", eye);
  prog.set("u_light_position", light);
  prog.set("u_light_intensity", glm::vec3(d2 * 0.8f));
  prog.set("u_normal_scaling", look.normal_scaling);
  prog.set("u_height_scaling", look.height_scaling);
  prog.set("u_exposure", look.exposure);
  prog.set("u_studio", look.studio ? 1 : 0);
  prog.set("u_viewport", viewport_size);
  prog.set("u_back_tint", look.back_tint);
  prog.set("u_shadows", shadows ? 1 : 0);
  prog.set("u_ao", occlusion ? 1 : 0);
  // Bump shows the fabric weave; Displacement moves vertices, so it uses the smooth bumps a
  // 50x50 mesh can follow without jaggies.
  const gl::Texture& height = displaced ? bumps_height_ : weave_height_;
  prog.set("u_texture_size", glm::vec2(height.width(), height.height()));
  prog.set("u_texture", 0);
  prog.set("u_height_texture", 1);
  prog.set("u_environment", 2);
  prog.set("u_shadow_map", int(kShadowCompareUnit));
  prog.set("u_shadow_depth", int(kShadowDepthUnit));
  prog.set("u_ambient_occlusion", int(kOcclusionUnit));
  fabric_.bind(0);
  height.bind(1);
  sky_.bind(2);
  if (shadows) shadow_->bind_for_lighting();
  if (occlusion) occlusion_->bind_result();
  draw_objects(prog, positions, normals, look, Pass::Shade);
  if (shadows) shadow_->release();
  mark(3);
  if (timing_) {
    const auto& ms = clock_->finish();
    times_ = {ms[0], ms[1], ms[2], clock_->uses_queries()};
  }
}

}  // namespace clothsim

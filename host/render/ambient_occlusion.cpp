#include "ambient_occlusion.hpp"

#include <glm/matrix.hpp>

namespace clothsim {

AmbientOcclusion::AmbientOcclusion(const std::filesystem::path& shaders)
    : occlude_(gl::Program::graphics(shaders / "fullscreen.vert", shaders / "occlude_ambient.frag")),
      blur_(gl::Program::graphics(shaders / "fullscreen.vert", shaders / "blur_ambient.frag")) {}

void AmbientOcclusion::begin_depth() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_framebuffer_);
  glGetIntegerv(GL_VIEWPORT, previous_viewport_);
  const int w = previous_viewport_[2], h = previous_viewport_[3];
  if (w != width_ || h != height_ || !depth_) {
    width_ = w;
    height_ = h;
    depth_.emplace(gl::Texture::target_2d(GL_DEPTH_COMPONENT32F, w, h, false, "occlusion depth"));
    raw_.emplace(gl::Texture::target_2d(GL_R8, w, h, false, "occlusion"));
    blurred_.emplace(gl::Texture::target_2d(GL_R8, w, h, false, "occlusion blurred"));
    depth_target_.emplace("occlusion depth pre-pass");
    depth_target_->attach(GL_DEPTH_ATTACHMENT, *depth_);
    raw_target_.emplace("occlusion");
    raw_target_->attach(GL_COLOR_ATTACHMENT0, *raw_);
    blurred_target_.emplace("occlusion blurred");
    blurred_target_->attach(GL_COLOR_ATTACHMENT0, *blurred_);
  }
  depth_target_->bind();
  glClear(GL_DEPTH_BUFFER_BIT);
}

void AmbientOcclusion::full_screen(gl::Program& prog, const gl::Framebuffer& target, const glm::mat4& projection,
                                   float radius) {
  prog.set("u_depth", 0);
  prog.set("u_inverse_projection", glm::inverse(projection));
  prog.set("u_viewport", glm::vec2(float(width_), float(height_)));
  prog.set("u_radius", radius);
  target.bind();
  prog.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void AmbientOcclusion::compute(const glm::mat4& projection, float radius) {
  glDisable(GL_DEPTH_TEST);
  empty_.bind();
  // The pre-pass's depths are read next, as a texture, by both passes; the raw occlusion by the blur.
  depth_->bind(0);
  occlude_.set("u_projection", projection);
  full_screen(occlude_, *raw_target_, projection, radius);
  raw_->bind(1);
  blur_.set("u_occlusion", 1);
  full_screen(blur_, *blurred_target_, projection, radius);
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous_framebuffer_));
  glViewport(previous_viewport_[0], previous_viewport_[1], previous_viewport_[2], previous_viewport_[3]);
}

void AmbientOcclusion::bind_result() const { blurred_->bind(kOcclusionUnit); }

}  // namespace clothsim

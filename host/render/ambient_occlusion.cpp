#include "ambient_occlusion.hpp"

#include <glm/matrix.hpp>

namespace clothsim {

AmbientOcclusion::AmbientOcclusion(const std::filesystem::path& shaders)
    : shaders_(shaders),
      occlude_(gl::Program::graphics(shaders / "fullscreen.vert", shaders / "occlude_ambient.frag")),
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

void AmbientOcclusion::compute(const glm::mat4& projection, float radius) {
  const glm::vec2 viewport{float(width_), float(height_)};
  glDisable(GL_DEPTH_TEST);
  empty_.bind();
  // The pre-pass's depths are read next, as a texture, by both passes.
  depth_->bind(0);
  occlude_.set("u_depth", 0);
  occlude_.set("u_projection", projection);
  occlude_.set("u_inverse_projection", glm::inverse(projection));
  occlude_.set("u_viewport", viewport);
  occlude_.set("u_radius", radius);
  raw_target_->bind();
  occlude_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);

  raw_->bind(1);
  blur_.set("u_depth", 0);
  blur_.set("u_occlusion", 1);
  blur_.set("u_inverse_projection", glm::inverse(projection));
  blur_.set("u_viewport", viewport);
  blur_.set("u_radius", radius);
  blurred_target_->bind();
  blur_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous_framebuffer_));
  glViewport(previous_viewport_[0], previous_viewport_[1], previous_viewport_[2], previous_viewport_[3]);
}

void AmbientOcclusion::bind_result() const { blurred_->bind(kOcclusionUnit); }

}  // namespace clothsim

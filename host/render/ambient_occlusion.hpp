// Screen-space ambient occlusion: a depth pre-pass of everything drawn, one sample per pixel
// at the viewport's size; shaders/occlude_ambient.frag estimates the occlusion from it and
// shaders/blur_ambient.frag smooths it; the lit shaders read the result at texture unit
// kOcclusionUnit, one texel per pixel (shaders/lighting.glsl).
#pragma once

#include <filesystem>
#include <optional>

#include <glm/mat4x4.hpp>

#include "objects.hpp"
#include "program.hpp"
#include "texture.hpp"

namespace clothsim {

inline constexpr GLuint kOcclusionUnit = 5;

class AmbientOcclusion {
 public:
  explicit AmbientOcclusion(const std::filesystem::path& shaders);

  // Sizes the targets to the caller's viewport (remade when it changes), binds the depth
  // pre-pass and clears it; the caller then draws everything with its depth programs
  // (depth.frag) and calls compute().
  void begin_depth();
  // The two full-screen passes, for the camera's `projection` and a reach of `radius` (m);
  // restores the caller's framebuffer and viewport.
  void compute(const glm::mat4& projection, float radius);
  void bind_result() const;  // at kOcclusionUnit

 private:
  // Draws `prog` over the whole of `target`, reading the depth pre-pass at unit 0.
  void full_screen(gl::Program& prog, const gl::Framebuffer& target, const glm::mat4& projection, float radius);

  gl::Program occlude_, blur_;
  gl::VertexArray empty_{"full-screen triangle"};
  int width_ = 0, height_ = 0;
  std::optional<gl::Texture> depth_, raw_, blurred_;
  std::optional<gl::Framebuffer> depth_target_, raw_target_, blurred_target_;
  GLint previous_framebuffer_ = 0;
  GLint previous_viewport_[4] = {0, 0, 0, 0};
};

}  // namespace clothsim

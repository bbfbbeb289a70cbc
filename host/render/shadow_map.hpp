// The key light's shadow map: its frustum fitted on the GPU to this frame's casters
// (shaders/fit_shadow_frustum.comp), a depth-only pass drawing them from the light, and the
// two samplers the lit shaders read it through (shaders/shadow.glsl).
#pragma once

#include <filesystem>

#include <glm/vec3.hpp>

#include "../../compute/layout.glsl"
#include "objects.hpp"
#include "program.hpp"
#include "texture.hpp"

namespace clothsim {

// Texture units of the shadow map (compared, raw) in the lit shaders; clear of units 0-2 (the
// material textures) and 5 (ambient occlusion), and of the compute passes' 8 and above.
inline constexpr GLuint kShadowCompareUnit = 3, kShadowDepthUnit = 4;

class ShadowMap {
 public:
  // size: texels per side of the square depth map.
  ShadowMap(const std::filesystem::path& shaders, int size);

  // Writes this frame's ShadowFrame from the `count` cloth positions in `positions` (read in
  // place) and the colliders' box [colliders_lo, colliders_hi] (lo > hi: none), seen from the
  // light at `light` whose disc has radius `light_radius` (m).
  void fit(const gl::Buffer& positions, int count, const glm::vec3& light, float light_radius,
           const glm::vec3& colliders_lo, const glm::vec3& colliders_hi);
  // Binds the map and clears it, with the slope-scaled offset on; the caller then draws the
  // casters with caster_program() and calls end() to restore its framebuffer and state.
  void begin();
  void end();
  gl::Program& caster_program() { return caster_; }
  // Binds the map for the lit shaders (kShadowCompareUnit, kShadowDepthUnit) and the frame at
  // BINDING_DRAW_SHADOW; release() takes the samplers off the units again.
  void bind_for_lighting() const;
  void release() const;

  // The frame the last fit() wrote (a read-back: for tests and diagnostics, never per frame).
  layout::ShadowFrame frame() const;
  int size() const { return size_; }

 private:
  int size_;
  gl::Texture depth_;
  gl::Framebuffer target_{"shadow map"};
  gl::Sampler compare_, raw_;
  gl::Program fit_, caster_;
  gl::Buffer frame_{"shadow frame"};
  GLint previous_framebuffer_ = 0;
  GLint previous_viewport_[4] = {0, 0, 0, 0};
};

}  // namespace clothsim

#include "shadow_map.hpp"

#include <string>

namespace clothsim {

ShadowMap::ShadowMap(const std::filesystem::path& shaders, int size)
    : size_(size),
      depth_(gl::Texture::target_2d(GL_DEPTH_COMPONENT32F, size, size, true, "shadow map depth")),
      compare_(true, true, 1.f), raw_(false, false, 1.f),
      fit_(gl::Program::compute(shaders / "fit_shadow_frustum.comp")),
      caster_(gl::Program::graphics(shaders / "shadow.vert", shaders / "depth.frag",
                                    {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}})) {
  target_.attach(GL_DEPTH_ATTACHMENT, depth_);
  frame_.allocate(sizeof(layout::ShadowFrame));
}

void ShadowMap::fit(const gl::Buffer& positions, int count, const glm::vec3& light, float light_radius,
                    const glm::vec3& colliders_lo, const glm::vec3& colliders_hi) {
  positions.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_POSITIONS);
  frame_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_SHADOW);
  fit_.set("u_count", count);
  fit_.set("u_light_position", light);
  fit_.set("u_light_radius", light_radius);
  fit_.set("u_colliders_lo", colliders_lo);
  fit_.set("u_colliders_hi", colliders_hi);
  fit_.set("u_map_size", float(size_));
  fit_.dispatch(1);
  // The shadow pass's vertex stage and the lit shaders' fragment stage read the frame next.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ShadowMap::begin() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_framebuffer_);
  glGetIntegerv(GL_VIEWPORT, previous_viewport_);
  target_.bind();
  glClear(GL_DEPTH_BUFFER_BIT);
  // Slope-scaled: a surface the light grazes gets more, so its own depths do not shadow it.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.f);
  frame_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_SHADOW);
}

void ShadowMap::end() {
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous_framebuffer_));
  glViewport(previous_viewport_[0], previous_viewport_[1], previous_viewport_[2], previous_viewport_[3]);
}

void ShadowMap::bind_for_lighting() const {
  depth_.bind(kShadowCompareUnit);
  depth_.bind(kShadowDepthUnit);
  compare_.bind(kShadowCompareUnit);
  raw_.bind(kShadowDepthUnit);
  frame_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_SHADOW);
}

void ShadowMap::release() const {
  glBindSampler(kShadowCompareUnit, 0);
  glBindSampler(kShadowDepthUnit, 0);
}

layout::ShadowFrame ShadowMap::frame() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the fit's writes, read back here
  layout::ShadowFrame f{};
  frame_.download(0, sizeof f, &f);
  return f;
}

}  // namespace clothsim

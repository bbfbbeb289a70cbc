// The skinned mesh colliders' buffers (layout.glsl, TEXTURE_SKINNED and its inputs): the fixed
// lists and the bind pose, uploaded when the constants bring another set; the palette, every
// substep (upload_control); the vertices and boxes skin_colliders and fit_collider_boxes write.
#include "gpu_state.hpp"

#include <algorithm>

namespace clothsim {

void GpuState::upload_skins(const Constants<float>& c) {
  // A view may not be empty: one dummy texel each without a skinned collider.
  auto or_dummy = [](std::vector<glm::vec4> v) { return v.empty() ? std::vector<glm::vec4>(1, glm::vec4(0.f)) : v; };
  std::vector<glm::vec4> palette(c.control.palette.begin(), c.control.palette.end());
  palette = or_dummy(std::move(palette));
  if (skin_palette_.size() == palette.size() * sizeof(glm::vec4)) {
    skin_palette_.upload(0, skin_palette_.size(), palette.data());
  } else {
    gl::upload_vector(skin_palette_, palette, GL_DYNAMIC_DRAW);
    skin_palette_view_.attach(skin_palette_, GL_RGBA32F);
  }
  const Vec4<float>* source = c.control.skinned.empty() ? nullptr : c.control.skinned.data();
  if (source == skin_source_ && skinned_.size() > 0) return;
  skin_source_ = source;
  // The lists in TEXTURE_SKIN_INDICES' order: bones, triangles, clusters, groups.
  std::vector<glm::uvec4> indices(c.skin.bones);
  for (const auto* list : {&c.skin.triangles, &c.skin.clusters, &c.skin.groups, &c.skin.supers})
    indices.insert(indices.end(), list->begin(), list->end());
  if (indices.empty()) indices.resize(1);
  gl::upload_vector(skin_indices_, indices, GL_STATIC_DRAW);
  gl::upload_vector(skin_weights_, or_dummy({c.skin.weights.begin(), c.skin.weights.end()}), GL_STATIC_DRAW);
  // The bind pose's section is read from here on; the others are the passes' from the first substep.
  gl::upload_vector(skinned_, or_dummy({c.control.skinned.begin(), c.control.skinned.end()}), GL_DYNAMIC_COPY);
  // Each mass's nearest skinned triangle, none yet (a cache: the searches find the same without
  // it), then the far records and the summed moves, zero: void (compute/nearest.glsl).
  nearest_slots_ = std::max<size_t>(1, size_t(c.count) * c.skin_meshes);
  std::vector<uint32_t> nearest(nearest_words(), 0u);
  std::fill_n(nearest.begin(), nearest_slots_, 0xFFFFFFFFu);
  gl::upload_vector(nearest_, nearest, GL_DYNAMIC_COPY);
  skin_indices_view_.attach(skin_indices_, GL_RGBA32UI);
  skin_weights_view_.attach(skin_weights_, GL_RGBA32F);
  skinned_view_.attach(skinned_, GL_RGBA32F);
}

std::vector<Vec4<float>> GpuState::download_skinned() const {
  if (skin_source_ == nullptr) return {};
  const auto texels = gl::download_vector<glm::vec4>(skinned_, 0, skinned_.size() / sizeof(glm::vec4));
  return {texels.begin(), texels.end()};
}

}  // namespace clothsim

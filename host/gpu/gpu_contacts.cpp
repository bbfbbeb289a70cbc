// The contact list on the GPU (compute/contact_list.glsl, docs/performance.md "The contact list"):
// advance and predict list the masses a collider may move, and xpbd's and multigrid's sweeps
// those a colour's correction may have pushed into one; collide_objects runs on those alone, one
// indirect dispatch sized by the list on the GPU, with no read-back.
#include "gpu_passes.hpp"

namespace clothsim {

bool GpuPasses::uses_contact_list() const { return constants_.has_colliders(); }

void GpuPasses::start_contact_list() {
  const size_t bytes = sizeof(layout::ContactListHeader) + size_t(model_.count()) * sizeof(uint32_t);
  if (contacts_.size() != bytes) contacts_.allocate(bytes);
  // No workgroups and no masses yet (y and z stay 1 for glDispatchComputeIndirect). The last
  // reader of the header, the previous collide_objects, ended with a BUFFER_UPDATE barrier.
  const layout::ContactListHeader empty{{0u, 1u, 1u, 0u}};
  contacts_.upload(0, sizeof empty, &empty);
  // On the scan's data point (layout.glsl), which the scan binds again before its next use.
  contacts_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CONTACT_LIST);
}

std::vector<uint32_t> GpuPasses::contact_list() const {
  if (contacts_.size() == 0) return {};
  const uint32_t count = gl::download_vector<layout::ContactListHeader>(contacts_, 0, 1)[0].dispatch_count.w;
  return gl::download_vector<uint32_t>(contacts_, sizeof(layout::ContactListHeader) / sizeof(uint32_t), count);
}

}  // namespace clothsim

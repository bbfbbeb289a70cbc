// The contact list on the GPU (compute/contact_list.glsl, docs/performance.md "The contact list"):
// advance and predict list the masses a collider may move; collide_objects runs on those alone, one
// indirect dispatch sized by the list on the GPU, with no read-back.
#include "gpu_passes.hpp"

namespace clothsim {

bool GpuPasses::uses_contact_list() const { return constants_.has_colliders(); }

void GpuPasses::start_contact_list() {
  const size_t bytes = sizeof(layout::ContactListHeader) + size_t(state_.model_.count()) * sizeof(uint32_t);
  if (state_.contacts_.size() != bytes) state_.contacts_.allocate(bytes);
  // No workgroups and no masses yet (y and z stay 1 for glDispatchComputeIndirect). The last
  // reader of the header, the previous collide_objects, ended with a BUFFER_UPDATE barrier.
  const layout::ContactListHeader empty{{0u, 1u, 1u, 0u}};
  state_.contacts_.upload(0, sizeof empty, &empty);
  // On the scan's data point (layout.glsl), which the scan binds again before its next use.
  state_.contacts_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CONTACT_LIST);
}

}  // namespace clothsim

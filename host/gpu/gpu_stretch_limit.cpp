// fabric's enforce_stretch_limit on the GPU (docs/model.md): the
// fixed passes of the length constraint, then the settling ones, each armed on the GPU from
// what the pass before it found, so that a settled substep skips them with no read-back.
#include "gpu_passes.hpp"

#include <algorithm>

namespace clothsim {

bool GpuPasses::enabled_colour(int colour) const {
  return state_.model_.colour_start[colour + 1] > state_.model_.colour_start[colour] && constants_.colour_enabled(state_.model_, colour);
}

void GpuPasses::enforce_stretch_limit() {
  if (constants_.stretch_passes_max <= constants_.stretch_passes) {
    length_constraint_passes(constants_.stretch_passes, PassId::stretch_fixed_passes);
    return;
  }
  // As the CPU twin: the fixed passes but the last, then the watched ones from that last one
  // (one, with none fixed) on.
  const int fixed = std::max(constants_.stretch_passes, 1);
  length_constraint_passes(fixed - 1, PassId::stretch_fixed_passes);
  settling_passes(fixed);
}

void GpuPasses::settling_passes(int fixed) {
  if (!settling_loaded_) load_rows(Build::settling);
  settling_loaded_ = true;
  const int colours = state_.model_.colours();
  const size_t bytes = sizeof(layout::StretchControl) + size_t(colours) * sizeof(layout::StretchDispatch);
  if (state_.stretch_control_.size() != bytes) {
    // Made once per model: the header zeroed (no flag, no passes counted), each colour's
    // workgroups in w for arm_stretch_pass to copy into x.
    std::vector<glm::uvec4> control(1 + colours, glm::uvec4(0));
    for (int c = 0; c < colours; ++c) {
      const uint32_t springs = state_.model_.colour_start[c + 1] - state_.model_.colour_start[c];
      control[1 + c] = {0u, 1u, 1u, gl::workgroups_for(springs, WORKGROUP_SIZE)};
    }
    gl::upload_vector(state_.stretch_control_, control);
  }
  bind_for_pass();
  // On the scan's point (layout.glsl), which the scan binds again before its next use.
  state_.stretch_control_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_STRETCH_CONTROL);
  state_.stretch_control_.bind(GL_DISPATCH_INDIRECT_BUFFER);
  for (int pass = fixed - 1; pass < constants_.stretch_passes_max; ++pass) {
    const size_t arm = size_t(PassId::arm_stretch_pass);
    programs_[arm].set(flag_[arm], int(pass == fixed - 1));
    dispatch_row(PassId::arm_stretch_pass);
    for (int colour = 0; colour < colours; ++colour) {
      if (!enabled_colour(colour)) continue;
      const uint32_t first = state_.model_.colour_start[colour];
      // Its workgroups from the colour's entry, which the arm set (0 where the last pass settled).
      dispatch_row(PassId::stretch_watched_passes, {first, state_.model_.colour_start[colour + 1] - first}, false,
                   GLintptr((1 + colour) * sizeof(layout::StretchDispatch)));
    }
  }
}

}  // namespace clothsim

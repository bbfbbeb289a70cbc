// The multigrid solver's GPU buffers (gpu_multigrid.cpp): the hierarchy's lists and the
// scratch of a solve, with their views (its programs are the pass table's, gpu_passes.hpp).
#pragma once

#include <memory>

#include "gpu_state.hpp"

namespace clothsim {

struct GpuMultigrid {
  // The hierarchy (layout.glsl: TEXTURE_MG_VERTICES, _LISTS, _FINE, _ORDER), static over a run.
  gl::Buffer vertices{"multigrid vertices"}, lists{"multigrid lists"}, fine{"multigrid fine parents"}, order{"multigrid order"};
  // A solve's scratch (BINDING_MG_RESIDUALS, _OFFSET, _RHS, _CORR).
  gl::Buffer residuals{"multigrid residuals"}, offset{"multigrid offsets"}, rhs{"multigrid rhs"}, corr{"multigrid corrections"};
  gl::BufferTexture vertices_view{"multigrid vertices view"}, lists_view{"multigrid lists view"};
  gl::BufferTexture fine_view{"multigrid fine parents view"}, order_view{"multigrid order view"};
  gl::BufferTexture corr_view{"multigrid corrections view"}, offset_view{"multigrid offsets view"};
  gl::BufferTexture residuals_view{"multigrid residuals view"}, rhs_view{"multigrid rhs view"};
  std::shared_ptr<const Hierarchy> hierarchy;  // what the buffers hold (Constants::hierarchy)
};

}  // namespace clothsim

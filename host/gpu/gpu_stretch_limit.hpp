// enforce_stretch_limit's settling passes on the GPU (gpu_stretch_limit.cpp): the watched
// length pass and the pass that arms the next one.
#pragma once

#include <string>

#include "gpu_simulator.hpp"

namespace clothsim {

struct GpuSettlingPasses {
  GpuSettlingPasses(const std::filesystem::path& dir, const ShaderFeatures& f)
      : watched(load_pass(dir, "solve_length_constraints", f,
                          {{"STRETCH_SETTLED", "(1.0 + 1.0 / " + std::to_string(1 << kStretchSettledBits) + ".0)"}})),
        arm(load_pass(dir, "arm_stretch_pass", f)),
        first(watched.location("u_first")),
        count(watched.location("u_count")),
        first_watched(arm.location("u_first_watched")) {}
  gl::Program watched;  // solve_length_constraints compiled with STRETCH_SETTLED: it raises the flag
  gl::Program arm;      // arm_stretch_pass
  GLint first, count, first_watched;
};

}  // namespace clothsim

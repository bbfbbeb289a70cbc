// Free GPU memory, where the driver tells: GL_NVX_gpu_memory_info (NVIDIA) or GL_ATI_meminfo
// (AMD). Mesa's llvmpipe and most other drivers have neither; there the check does not apply
// and an allocation that fails reports GL_OUT_OF_MEMORY instead (gl::Buffer::allocate).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cloth.hpp"
#include "scene.hpp"

namespace clothsim {

struct GpuMemoryInfo {
  uint64_t available_bytes = 0;
  std::string source;  // the extension that said so
};

// Needs a current context; nullopt when the driver has neither extension.
std::optional<GpuMemoryInfo> available_gpu_memory();

// What the simulator's buffers (and its divergence guard's) take for this cloth.
uint64_t simulator_bytes(const ClothModel& model);

// The message when `needed` bytes do not fit (names the scene's grid key), else nullopt.
std::optional<std::string> memory_shortfall(const Scene& scene, const ClothModel& model, uint64_t needed,
                                            const std::optional<GpuMemoryInfo>& available);

// Throws SceneError (exit 2) when the driver reports less free memory than the cloth needs.
void check_gpu_memory(const Scene& scene, const ClothModel& model);

}  // namespace clothsim

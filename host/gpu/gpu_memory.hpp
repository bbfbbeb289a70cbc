// Free GPU memory, where the driver tells: GL_NVX_gpu_memory_info (NVIDIA; every Gallium driver
// since Mesa 24) or GL_ATI_meminfo (AMD). Where it does not, or where the renderer is Mesa's
// software rasterizer (its memory is the machine's), the check does not apply and an allocation
// that fails reports GL_OUT_OF_MEMORY instead (gl::Buffer::allocate).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cloth/cloth.hpp"
#include "scene/scene.hpp"

namespace clothsim {

struct GpuMemoryInfo {
  uint64_t available_bytes = 0;
  std::string source;  // the extension that said so
};

// What the driver's reports say is free (KiB as the extensions give them, nullopt where the
// driver lacks one), given its GL_RENDERER: nullopt, no check, for Mesa's software
// rasterizers (their memory is the machine's) and where a report says 0 (not counted).
std::optional<GpuMemoryInfo> memory_report(const std::string& renderer, std::optional<int64_t> nvx_available_kib,
                                           std::optional<int64_t> ati_free_kib);

// Needs a current context: memory_report of the current driver.
std::optional<GpuMemoryInfo> available_gpu_memory();

// What the simulator's buffers (and its divergence guard's) take for this cloth.
uint64_t simulator_bytes(const ClothModel& model);

// The message when `needed` bytes do not fit (names the scene's grid key), else nullopt.
std::optional<std::string> memory_shortfall(const Scene& scene, const ClothModel& model, uint64_t needed,
                                            const std::optional<GpuMemoryInfo>& available);

// Throws SceneError (exit 2) when the driver reports less free memory than the cloth needs.
void check_gpu_memory(const Scene& scene, const ClothModel& model);

}  // namespace clothsim

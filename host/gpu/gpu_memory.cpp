#include "gpu_memory.hpp"

#include <cstring>

#include <fmt/format.h>

#include "context.hpp"
#include "objects.hpp"
#include "reference/spatial_hash.hpp"
#include "../../compute/layout.glsl"

namespace clothsim {
namespace {

// Not in the generated loader (glad is made for core 4.3 + KHR_debug only).
constexpr GLenum kNvxCurrentAvailableVidmem = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, KiB
constexpr GLenum kAtiVboFreeMemory = 0x87FB;           // GL_VBO_FREE_MEMORY_ATI: 4 ints, [0] total free KiB

bool has_extension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

}  // namespace

std::optional<GpuMemoryInfo> memory_report(const std::string& renderer, std::optional<int64_t> nvx_available_kib,
                                           std::optional<int64_t> ati_free_kib) {
  // Mesa's software rasterizers draw from the machine's memory, which the driver does not
  // track as a device's: since Mesa 24 every Gallium driver exposes GL_NVX_gpu_memory_info,
  // and llvmpipe (Mesa 25.0) answers 0 or a few MiB there, which refused a 256^2 cloth on a
  // machine with 24 GiB free. There, as with no report, an allocation that fails says so
  // (GL_OUT_OF_MEMORY, gl::Buffer::allocate).
  for (const char* software : {"llvmpipe", "softpipe"})
    if (renderer.find(software) != std::string::npos) return std::nullopt;
  // Nothing free at all is a driver that does not count, not a full GPU: a context could not
  // have been made on one.
  if (nvx_available_kib && *nvx_available_kib > 0)
    return GpuMemoryInfo{uint64_t(*nvx_available_kib) * 1024, "GL_NVX_gpu_memory_info"};
  if (ati_free_kib && *ati_free_kib > 0) return GpuMemoryInfo{uint64_t(*ati_free_kib) * 1024, "GL_ATI_meminfo"};
  return std::nullopt;
}

std::optional<GpuMemoryInfo> available_gpu_memory() {
  std::optional<int64_t> nvx, ati;
  if (has_extension("GL_NVX_gpu_memory_info")) {
    GLint kib = 0;
    glGetIntegerv(kNvxCurrentAvailableVidmem, &kib);
    nvx = kib;
  }
  if (has_extension("GL_ATI_meminfo")) {
    GLint kib[4] = {};
    glGetIntegerv(kAtiVboFreeMemory, kib);
    ati = kib[0];
  }
  return memory_report(gl::gl_renderer_string(), nvx, ati);
}

uint64_t simulator_bytes(const ClothModel& model) {
  const uint64_t n = uint64_t(model.count()), table = hash_table_size(uint32_t(n));
  // pos, disp, forces, normals, the self-collision output, the kept copy, the tethers, the
  // particles' mass and material and the rest positions (bounded contact only; counted always); the springs, their gather entries (two per spring), the
  // triangles and their corner entries (three per triangle); the hash's entries per particle and
  // its count and start per bucket (scan sums are less than 1 % more).
  const uint64_t springs = model.springs.size(), triangles = model.triangles.size();
  return n * (9 * sizeof(glm::vec4) + 3 * sizeof(uint32_t)) + springs * (sizeof(layout::SpringTexel) + 2 * sizeof(glm::uvec2)) +
         triangles * (sizeof(glm::uvec4) + 3 * sizeof(uint32_t)) + (2 * table + 1) * sizeof(uint32_t);
}

std::optional<std::string> memory_shortfall(const Scene& scene, const ClothModel& model, uint64_t needed,
                                            const std::optional<GpuMemoryInfo>& available) {
  if (!available || needed <= available->available_bytes) return std::nullopt;
  const std::string what = model.is_grid()
                               ? fmt::format("cloth.num_width_points: a {}x{} grid needs", model.nw, model.nh)
                               : fmt::format("cloth: {} particles need", model.count());
  return fmt::format("{}: {} about {:.0f} MiB of GPU memory, more than "
                     "the {:.0f} MiB this GPU has free ({}); use fewer points, close other programs using the "
                     "GPU, or run on the CPU: --backend cpu",
                     scene.source, what, double(needed) / 1048576.0,
                     double(available->available_bytes) / 1048576.0, available->source);
}

void check_gpu_memory(const Scene& scene, const ClothModel& model) {
  if (auto message = memory_shortfall(scene, model, simulator_bytes(model), available_gpu_memory()))
    throw SceneError(*message);
}

}  // namespace clothsim

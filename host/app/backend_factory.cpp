#include <fmt/format.h>

#include "cli_common.hpp"
#include "io/host_memory.hpp"
#include "debug_output.hpp"
#include "gpu_simulator.hpp"

namespace clothsim {

std::unique_ptr<gl::GlContext> require_headless_context() {
  std::string why;
  gl::ContextOptions options;
#ifndef NDEBUG
  options.debug = true;  // debug builds report every GL error as it happens (KHR_debug)
#endif
  auto context = gl::create_headless_context(&why, options);
  if (!context)
    throw ExitError(kExitNoContext,
                    fmt::format("no OpenGL 4.3 context could be created: {}\n"
                                "  Headless runs need EGL with an OpenGL 4.3 driver: on Debian install "
                                "libegl-mesa0 and libgl1-mesa-dri (llvmpipe, no GPU needed), or a GPU driver.\n"
                                "  Or run on the CPU reference: --backend cpu",
                                why));
#ifndef NDEBUG
  gl::enable_debug_output(gl::DebugMode::Errors);
#endif
  if (const std::string notice = gl::software_renderer_notice(); !notice.empty()) fmt::print(stderr, "{}\n", notice);
  return context;
}

std::unique_ptr<Backend> make_backend(BackendKind kind, const Scene& scene, const ClothModel& model) {
  if (kind == BackendKind::Cpu) {
    // Positions, displacements, forces and normals (4 doubles each) and a multiplier per spring.
    const uint64_t bytes = (uint64_t(model.count()) * 4 + model.springs.size()) * 4 * sizeof(double);
    return allocating(fmt::format("the CPU backend's state for {} particles and {} springs", model.count(),
                                  model.springs.size()),
                      bytes, [&] { return std::make_unique<CpuBackend<double>>(scene, model); });
  }
  auto context = require_headless_context();
  return std::make_unique<GpuBackend>(std::move(context), scene, model, find_project_root() / "compute");
}

}  // namespace clothsim

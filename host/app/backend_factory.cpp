#include "cli_common.hpp"

namespace clothsim {

std::unique_ptr<Backend> make_backend(BackendKind kind, const Scene& scene, const ClothModel& model) {
  if (kind == BackendKind::Cpu) return std::make_unique<CpuBackend<double>>(scene, model);
  throw ExitError(kExitBadInput, "--backend gpu: the GPU backend is not available in this build yet; use --backend cpu");
}

}  // namespace clothsim

// Checkpoints on the GPU: the two state buffers read back and uploaded bit for bit, so a run
// continued from a saved state is the run that never stopped.
#include "gl_test_support.hpp"

#include <unistd.h>

#include <filesystem>

#include "checkpoint.hpp"
#include "gpu_simulator.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

TEST_CASE("GPU: 2N frames equal N frames, saved, loaded and N more, bitwise", "[gpu][checkpoint]") {
  REQUIRE_GL_CONTEXT();
  // A sphere and self-collision, so every pass of the step runs from the loaded state.
  const Scene s = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0],[6,0]]"},
                                   R"(, "sphere": {"origin": [0.5, 0.6, 0.5], "radius": 0.2, "friction": 0.3})");
  const ClothModel m = build_cloth(s);
  const std::filesystem::path compute = test::source_path("compute");
  const std::string file =
      (std::filesystem::temp_directory_path() / fmt::format("clothsim_test_gpu_checkpoint_{}.state", getpid())).string();
  const int n = 6;

  GpuBackend whole(nullptr, s, m, compute);  // runs in the tests' shared context
  for (int f = 0; f < 2 * n; ++f) whole.step_frame();
  {
    GpuBackend first(nullptr, s, m, compute);
    for (int f = 0; f < n; ++f) first.step_frame();
    write_checkpoint(file, {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, first.name(), first.save_state()});
  }
  const Checkpoint c = read_checkpoint(file);
  std::filesystem::remove(file);
  GpuBackend second(nullptr, s, m, compute);
  check_fits(c, file, s, m, second.scalar_bytes(), second.name());
  second.load_state(c.state);
  CHECK(second.save_state().positions == c.state.positions);
  for (int f = 0; f < n; ++f) second.step_frame();

  const SavedState a = whole.save_state(), b = second.save_state();
  CHECK(b.frame == 2 * n);
  CHECK(a.time == b.time);
  CHECK(a.positions == b.positions);
  CHECK(a.displacement == b.displacement);
  // The guard counts on from the loaded frame: the checks taken are frames N+1 .. 2N.
  const std::vector<FrameCheck> checks = second.take_checks(true);
  REQUIRE(!checks.empty());
  CHECK(checks.back().frame == 2 * n);
  CHECK_NO_GL_ERRORS();
}

// Checkpoints on the GPU: the two state buffers read back and uploaded bit for bit, so a run
// continued from a saved state is the run that never stopped.
#include "gl_test_support.hpp"

#include <unistd.h>

#include <filesystem>

#include "export/checkpoint.hpp"
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

namespace {

Scene gpu_scene_file(const std::string& name, const std::vector<std::string>& sets = {}) {
  return load_scene(test::source_path("scenes/" + name + ".json"), sets);
}

// 2N frames straight against N, saved to a file and read back, then N more: bitwise.
void check_gpu_resumes_bitwise(const Scene& s, int n) {
  const ClothModel m = build_cloth(s);
  const std::filesystem::path compute = test::source_path("compute");
  const std::string file =
      (std::filesystem::temp_directory_path() / fmt::format("clothsim_test_gpu_resume_{}.state", getpid())).string();
  GpuBackend whole(nullptr, s, m, compute);
  for (int f = 0; f < 2 * n; ++f) whole.step_frame();
  {
    GpuBackend first(nullptr, s, m, compute);
    for (int f = 0; f < n; ++f) first.step_frame();
    write_checkpoint(file, {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, first.name(), first.save_state()});
  }
  const Checkpoint c = read_checkpoint(file);
  std::filesystem::remove(file);
  CHECK(c.state.dt == s.dt());
  GpuBackend second(nullptr, s, m, compute);
  second.load_state(c.state);
  for (int f = 0; f < n; ++f) second.step_frame();
  const SavedState a = whole.save_state(), b = second.save_state();
  CHECK(b.frame == 2 * n);
  CHECK(a.time == b.time);
  CHECK(test::mismatches(a.positions, b.positions) == 0);
  CHECK(test::mismatches(a.displacement, b.displacement) == 0);
  CHECK(a.positions != GpuBackend(nullptr, s, m, compute).save_state().positions);  // it moved
}

}  // namespace

TEST_CASE("GPU: save and resume is bitwise on living (moving sphere and pins, gusts), flag_pole (wind, fabric) and hang_xpbd",
          "[gpu][checkpoint][long]") {
  REQUIRE_GL_CONTEXT();
  SECTION("living") { check_gpu_resumes_bitwise(gpu_scene_file("living"), 10); }
  SECTION("flag_pole") { check_gpu_resumes_bitwise(gpu_scene_file("flag_pole"), 4); }
  SECTION("hang_xpbd") { check_gpu_resumes_bitwise(gpu_scene_file("hang_xpbd"), 8); }
  CHECK_NO_GL_ERRORS();
}

// fabric's predict reads the solve offsets of the substep before: the state file keeps them.
TEST_CASE("GPU: save and resume is bitwise under the fabric solver (sphere: its solve offsets saved)",
          "[gpu][checkpoint][long]") {
  REQUIRE_GL_CONTEXT();
  check_gpu_resumes_bitwise(gpu_scene_file("sphere", {"simulation.solver=\"fabric\"", "cloth.density=0.15", "cloth.ks=5000"}), 6);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("GPU: a state loaded with another substep length is rescaled as the reference rescales it", "[gpu][checkpoint]") {
  REQUIRE_GL_CONTEXT();
  // Undamped (damping is per substep, so it would differ between 30 and 60 substeps anyway).
  const std::vector<std::string> small = {"cloth.num_width_points=17", "cloth.num_height_points=17",
                                          "cloth.pinned=[[0,0],[16,0]]", "cloth.damping=0"};
  std::vector<std::string> sets30 = small, sets60 = small;
  sets30.push_back("simulation.simulation_steps=30");
  sets60.push_back("simulation.simulation_steps=60");
  const Scene s30 = gpu_scene_file("pinned2", sets30), s60 = gpu_scene_file("pinned2", sets60);
  const ClothModel m = build_cloth(s30);
  const std::filesystem::path compute = test::source_path("compute");
  GpuBackend straight(nullptr, s30, m, compute);
  for (int f = 0; f < 30; ++f) straight.step_frame();
  const SavedState saved = straight.save_state();
  REQUIRE(saved.dt == s30.dt());
  straight.step_frame();
  const double ke31 = measure(s30, m, straight.snapshot()).kinetic;

  GpuBackend resumed(nullptr, s60, m, compute);
  resumed.load_state(saved);
  CpuBackend<float> reference(s60, m);
  reference.load_state(saved);
  const SavedState gpu = resumed.save_state(), cpu = reference.save_state();
  CHECK(test::mismatches(gpu.displacement, cpu.displacement) == 0);  // rounded alike
  CHECK(test::mismatches(gpu.displacement, saved.displacement) > 0);  // and rescaled
  CHECK(gpu.dt == s60.dt());
  resumed.step_frame();
  const double ke31_60 = measure(s60, m, resumed.snapshot()).kinetic;
  INFO("frame 31: " << ke31 << " J at 30 substeps, " << ke31_60 << " J resumed at 60");
  CHECK(std::abs(ke31_60 - ke31) <= 0.01 * ke31);
  CHECK_NO_GL_ERRORS();
}

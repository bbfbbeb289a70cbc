// The fabric solver on the GPU (docs/solvers.md): stability over ks 10..1e9 at fabric density,
// and the dispatches per substep bench reports, within issue 43's budget. On llvmpipe each run
// also equals the float reference bit for bit.
#include <catch2/catch.hpp>

#include <cmath>

#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "pass_check.hpp"
#include "hanging_cloth.hpp"

using namespace clothsim;

namespace {


// `frames` frames on the GPU and, on llvmpipe, on the float reference too (bit for bit).
State<float> run_both(const Scene& s, const ClothModel& m, int frames, bool* diverged) {
  GpuSimulator gpu(s, m, test::source_path("compute"));
  CpuBackend<float> cpu(s, m);
  const bool exact = gl::gl_renderer_is_llvmpipe();
  *diverged = false;
  for (int f = 0; f < frames; ++f) {
    gpu.step_frame();
    if (exact) cpu.step_frame();
    for (const FrameCheck& check : gpu.passes().divergence().take(f + 1 == frames))
      *diverged = *diverged || divergence_message(s, m, check).has_value();
  }
  State<float> g;
  gpu.download(g);
  if (exact) {
    const Deviation d = deviation(g.pos, cpu.state().pos);
    INFO("GPU - CPU (float) " << d.max << " m");
    CHECK(d.bitwise);
  }
  return g;
}

}  // namespace

TEST_CASE("fabric on the GPU: no NaN and no divergence for ks from 10 to 1e9 at fabric density", "[gpu][fabric][long]") {
  REQUIRE_GL_CONTEXT();
  for (double ks : test::kStiffnesses) {
    const Scene s = test::hanging_cloth(17, ks);
    const ClothModel m = build_cloth(s);
    bool diverged = false;
    const State<float> g = run_both(s, m, 60, &diverged);
    bool finite = true;
    for (const auto& p : g.pos) finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    INFO("ks " << ks);
    CHECK(!diverged);
    CHECK(finite);
  }
  CHECK_NO_GL_ERRORS();
}

// Each solver's substep issues what dispatches_per_substep counts (bench's figure), and
// fabric's stays within issue 43's budget on the 33² cloth: 25 without self-collision, 40 with.
TEST_CASE("a substep issues the dispatches dispatches_per_substep counts, fabric's within 25 (40 with "
          "self-collision)", "[gpu][fabric]") {
  REQUIRE_GL_CONTEXT();
  for (bool self_collision : {false, true}) {
    int per_substep[2];
    for (Solver solver : {Solver::Classic, Solver::Fabric}) {
      Scene s = test::hanging_cloth(33);
      s.simulation.solver = solver;
      s.simulation.self_collision = self_collision;
      const ClothModel m = build_cloth(s);
      GpuSimulator gpu(s, m, test::source_path("compute"));
      const GpuCounters before = gpu.passes().counters();
      gpu.step();
      const int k = solver == Solver::Fabric;
      per_substep[k] = int(gpu.passes().counters().dispatches - before.dispatches);
      CHECK(per_substep[k] == gpu.passes().dispatches_per_substep());
    }
    INFO("self-collision " << self_collision << ": classic " << per_substep[0] << ", fabric " << per_substep[1]);
    CHECK(per_substep[1] <= (self_collision ? 40 : 25));
    if (!self_collision) CHECK(per_substep[0] == 13);
  }
  CHECK_NO_GL_ERRORS();
}

// Settling passes (simulation.stretch_passes_max) dispatch every watched pass up to the cap,
// whether it runs or not (a skipped one's workgroups are 0), so the count bench reports is what
// a substep issues: with 3 fixed passes and up to 7 in all, 2 fixed passes of every colour, then
// 5 watched ones, each after its arm_stretch_pass.
TEST_CASE("a substep with settling passes issues the dispatches dispatches_per_substep counts", "[gpu][fabric]") {
  REQUIRE_GL_CONTEXT();
  {
    Scene s = test::hanging_cloth(33);
    s.simulation.self_collision = false;
    s.simulation.stretch_passes = 3;
    const ClothModel m = build_cloth(s);
    GpuSimulator fixed(s, m, test::source_path("compute"));
    s.simulation.stretch_passes_max = 7;
    GpuSimulator gpu(s, m, test::source_path("compute"));
    const GpuCounters before = gpu.passes().counters();
    gpu.step();
    CHECK(int(gpu.passes().counters().dispatches - before.dispatches) == gpu.passes().dispatches_per_substep());
    const int colours = m.colours();
    CHECK(gpu.passes().dispatches_per_substep() - fixed.passes().dispatches_per_substep() == 2 * colours + 5 * (colours + 1) - 3 * colours);
  }
  CHECK_NO_GL_ERRORS();
}

// The fabric solver on the CPU reference (docs/solvers.md): stable for any ks at 30 substeps
// and fabric density, where the classic solver is not; and the vertical jitter that scales
// with the spacing. (Its stiffness at any resolution: tests/test_fabric.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>

#include "backend.hpp"
#include "analysis/diagnostics.hpp"
#include "test_helpers.hpp"
#include "hanging_cloth.hpp"

using namespace clothsim;

TEST_CASE("fabric: no NaN and no divergence for ks from 10 to 1e9 at fabric density (CPU reference)", "[reference][fabric]") {
  for (double ks : test::kStiffnesses) {
    const Scene s = test::hanging_cloth(17, ks);
    const ClothModel m = build_cloth(s);
    CpuBackend<float> cpu(s, m);
    bool diverged = false;
    for (int f = 0; f < 60; ++f) {
      cpu.step_frame();
      for (const FrameCheck& check : cpu.take_checks(true))
        diverged = diverged || divergence_message(s, m, check).has_value();
    }
    const ClothStats st = measure(s, m, cpu.snapshot());
    INFO("ks " << ks << ": max stretch " << st.max_stretch_ratio);
    CHECK(!diverged);
    CHECK(st.finite);
  }
}

TEST_CASE("the classic solver diverges on the same fabric cloth that fabric keeps (why fabric exists)", "[reference][fabric]") {
  Scene s = test::hanging_cloth(33);
  s.simulation.solver = Solver::Classic;
  const ClothModel m = build_cloth(s);
  CpuBackend<float> cpu(s, m);
  bool diverged = false;
  for (int f = 0; f < 60 && !diverged; ++f) {
    cpu.step_frame();
    for (const FrameCheck& check : cpu.take_checks(true))
      diverged = diverged || divergence_message(s, m, check).has_value();
  }
  CHECK(diverged);
}

TEST_CASE("the vertical jitter is at most 5 % of the spacing, and the classic 1 mm at the classic spacing", "[cloth][long]") {
  CHECK(jitter_amplitude(1.0 / 49) == 1e-3);
  CHECK(jitter_amplitude(0.5) == 1e-3);
  for (int n : {50, 257, 1024}) {
    const Scene s = test::make_scene(n, n, 1);
    const ClothModel m = build_cloth(s);
    const double spacing = 1.0 / (n - 1);
    double largest = 0;
    for (const auto& p : m.initial) largest = std::max(largest, std::abs(p.z));
    INFO(n << "²: largest offset " << largest << " m, spacing " << spacing << " m");
    CHECK(largest <= 0.05 * spacing);
    CHECK(largest > 0.04 * std::min(spacing, 1.0 / 49));  // it is still there
  }
  // The classic cloth is exactly as before: the offsets of a 50 x 50 cloth are the hash times 1e-3.
  const ClothModel classic = build_cloth(test::make_scene(50, 50, 1));
  for (uint32_t i : {0u, 7u, 2499u}) CHECK(classic.initial[i].z == vertical_offset(i, 1e-3));
}

// heap256's collapse at 65² under a limit of 2 %, which its cloth leans on once it meets the
// floor: the sweep alone leaves springs over it (fabric's sweep ends each substep with a colour
// that can pull a spring limited before it out again), settling passes
// (simulation.stretch_passes_max) run until no spring is over by more than 2^-16 of its limit,
// and a substep with none over runs none (docs/model.md, step 7).
TEST_CASE("fabric: settling passes hold a tight max_stretch at every frame where the sweep alone does not, and "
          "run only while a spring is over",
          "[reference][fabric][slow]") {
  auto worst_stretch = [](int most, int frames, uint64_t* settling) {
    return test::worst_stretch_over_frames(
        load_scene(std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "scenes" / "heap256.json",
                   {"cloth.num_width_points=65", "cloth.num_height_points=65", "simulation.max_stretch=0.02",
                    "simulation.stretch_passes=0", "simulation.stretch_passes_max=" + std::to_string(most)}),
        frames, settling);
  };
  uint64_t none = 0, first_frame = 0, settling = 0;
  const double alone = worst_stretch(-1, 40, &none);
  worst_stretch(100, 1, &first_frame);  // falling free: nothing near its limit
  const double settled = worst_stretch(100, 40, &settling);
  INFO("largest stretch at any of 40 frames: " << alone << " with the sweep alone, " << settled << " with up to 100 "
                                               "passes (" << settling << " settling passes in 1,200 substeps)");
  CHECK(none == 0);
  CHECK(first_frame == 0);
  CHECK(alone > 1.025);
  CHECK(settled <= 1.02 * (1 + 1.0 / 65536) + 1e-5);  // the limit, to the settling tolerance and float rounding
  CHECK(settling > 0);
  CHECK(settling < 98 * 1200 / 4);  // most substeps settle well before the cap
}

// The xpbd solver on the CPU reference (docs/model.md): as stiff at 65² as at 33², stable for
// any ks at 30 substeps and fabric density, where the classic solver is not; and the vertical
// jitter that scales with the spacing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>

#include "backend.hpp"
#include "analysis/diagnostics.hpp"
#include "test_helpers.hpp"
#include "xpbd_scenes.hpp"

using namespace clothsim;

TEST_CASE("xpbd: a hanging cloth's bottom centre is within 2 cm at 33² and 65² (CPU reference)", "[reference][xpbd][long]") {
  double y[2];
  int k = 0;
  for (int n : {33, 65}) {
    const Scene s = test::hanging_cloth(n);
    const ClothModel m = build_cloth(s);
    CpuBackend<float> cpu(s, m);
    for (int f = 0; f < 180; ++f) cpu.step_frame();
    const glm::dvec3 bottom(cpu.state().pos[m.index((n - 1) / 2, 0)]);
    INFO(n << "²: bottom centre at " << bottom.x << ", " << bottom.y << ", " << bottom.z);
    CHECK(std::isfinite(bottom.y));
    y[k++] = bottom.y;
  }
  INFO("bottom centre y: " << y[0] << " m at 33², " << y[1] << " m at 65²");
  CHECK(std::abs(y[0] - y[1]) <= 0.02);
  CHECK(y[0] < 0.0);  // it really hangs below where its bottom edge started
}

TEST_CASE("xpbd: no NaN and no divergence for ks from 10 to 1e9 at fabric density (CPU reference)", "[reference][xpbd]") {
  for (double ks : test::kXpbdStiffnesses) {
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

TEST_CASE("the classic solver diverges on the same fabric cloth that xpbd keeps (why xpbd exists)", "[reference][xpbd]") {
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

TEST_CASE("xpbd: a grid's tether is the straight rest distance to its nearest pin along the cloth", "[xpbd]") {
  const Scene s = test::hanging_cloth(33);
  const ClothModel m = build_cloth(s);
  int tethered = 0;
  for (int i = 0; i < m.count(); ++i) {
    const int pin = m.tether_pin[size_t(i)];
    if (pin < 0) continue;
    ++tethered;
    CHECK(m.tether_rest[size_t(i)] == Approx(glm::length(m.initial[size_t(i)] - m.initial[size_t(pin)])).epsilon(1e-12));
  }
  CHECK(tethered == m.count() - 2);
  // The bottom centre: 0.5 m across and 1 m down from either top corner, not the 8-neighbour
  // path's 1.04 m.
  const int bottom_centre = m.index(16, 0);
  CHECK(m.tether_rest[size_t(bottom_centre)] == Approx(std::sqrt(1.25)).epsilon(1e-3));
}

TEST_CASE("xpbd: the tethers hold a soft hanging cloth to 1 % over its rest distances from the pins, and without "
          "them it stretches further",
          "[xpbd][long]") {
  // ks 20: soft enough that the cloth's own springs let it sag far more than 1 %.
  auto worst_ratio = [](const std::string& tether_stretch) {
    Scene s = test::hanging_cloth(33, 20);
    s.simulation.tether_stretch = std::stod(tether_stretch);
    const ClothModel m = build_cloth(s);
    CpuBackend<double> cpu(s, m);
    for (int f = 0; f < 120; ++f) cpu.step_frame();
    double worst = 0;
    const auto& pos = cpu.state().pos;
    for (int i = 0; i < m.count(); ++i)
      if (const int pin = m.tether_pin[size_t(i)]; pin >= 0)
        worst = std::max(worst, glm::length(glm::dvec3(pos[size_t(i)]) - glm::dvec3(pos[size_t(pin)])) /
                                    m.tether_rest[size_t(i)]);
    return worst;
  };
  const double with = worst_ratio("0.01"), without = worst_ratio("100");
  INFO("largest distance from the pin over the tether length: " << with << " with tethers, " << without
                                                               << " without");
  CHECK(with <= 1.01 + 1e-3);  // the sweep after predict may undo a little of it
  CHECK(without > 1.05);
}

// heap256's collapse at 65², its thickness unchanged (2.6 mm): the cloth meets the floor and the sweep's later colours pull springs the earlier ones had limited
// back over max_stretch. stretch_passes passes of the limit alone after the sweep hold it at the
// end of every substep, so at every frame (docs/model.md).
TEST_CASE("xpbd: stretch_passes hold max_stretch at every frame of a 65² heap, which one sweep does not",
          "[reference][xpbd][slow]") {
  auto worst_stretch = [](int passes) {
    return test::worst_stretch_over_frames(
        load_scene(std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "scenes" / "heap256.json",
                   {"cloth.num_width_points=65", "cloth.num_height_points=65", "simulation.solver=\"xpbd\"",
                    "simulation.stretch_passes=" + std::to_string(passes), "simulation.stretch_passes_max=-1"}),
        60);
  };
  const double one_sweep = worst_stretch(0), held = worst_stretch(4);
  INFO("largest stretch at any frame: " << one_sweep << " with the sweep alone, " << held << " with 4 passes after it");
  CHECK(one_sweep > 1.15);
  CHECK(held <= 1.1001);  // the limit of 1.1, to float rounding
}

// The same heap under a limit of 2 %, which its cloth leans on over long runs of springs once it
// meets the floor: a fixed count of passes leaves them over (a pass of Gauss-Seidel moves a
// correction a few springs along), settling passes (simulation.stretch_passes_max) run until no
// spring is over by more than 2^-16 of its limit, and a substep with none over runs none.
TEST_CASE("xpbd: settling passes hold a tight max_stretch at every frame where fixed passes do not, and run only "
          "while a spring is over",
          "[reference][xpbd][slow]") {
  auto worst_stretch = [](int most, int frames, uint64_t* settling) {
    return test::worst_stretch_over_frames(
        load_scene(std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "scenes" / "heap256.json",
                   {"cloth.num_width_points=65", "cloth.num_height_points=65", "simulation.solver=\"xpbd\"",
                    "simulation.max_stretch=0.02",
                    "simulation.stretch_passes=2", "simulation.stretch_passes_max=" + std::to_string(most)}),
        frames, settling);
  };
  uint64_t none = 0, first_frame = 0, settling = 0;
  const double fixed = worst_stretch(-1, 40, &none);
  worst_stretch(100, 1, &first_frame);  // falling free: nothing near its limit
  const double settled = worst_stretch(100, 40, &settling);
  INFO("largest stretch at any of 40 frames: " << fixed << " with 2 passes, " << settled << " with up to 100 ("
                                               << settling << " settling passes in 1,200 substeps)");
  CHECK(none == 0);
  CHECK(first_frame == 0);
  CHECK(fixed > 1.03);
  CHECK(settled <= 1.02 * (1 + 1.0 / 65536) + 1e-5);  // the limit, to the settling tolerance and float rounding
  CHECK(settling > 0);
  CHECK(settling < 98 * 1200 / 4);  // most substeps settle well before the cap
}

// Coulomb friction of the fabric solver (docs/model.md, "Coulomb friction (fabric)"): a cloth on a
// plane tilted by theta holds when tan theta < mu and slides with g (sin theta - mu cos theta)
// when tan theta > mu, at 15, 30 and 60 substeps alike, on the CPU reference (float, the GPU's
// twin). tests/test_gpu_contact.cpp checks that the GPU gives the same floats.
#include <catch2/catch.hpp>

#include "backend.hpp"
#include "friction_cases.hpp"

using namespace clothsim;

namespace {

constexpr int kFrames = 90;  // 1 s at 90 frames/s
constexpr double kSeconds = 1.0;

test::SlopeMotion run_slope(const test::Slope& s) {
  CpuBackend<float> cpu(s.scene, s.model);
  for (int f = 0; f < kFrames; ++f) cpu.step_frame();
  return test::slope_motion(s, cpu.state().pos);
}

}  // namespace

TEST_CASE("fabric: a cloth on a slope with tan theta < mu stays put, at 15, 30 and 60 substeps", "[friction]") {
  for (auto [theta, mu] : {std::pair{20.0, 0.5}, std::pair{35.0, 0.75}}) {
    for (int steps : {15, 30, 60}) {
      const test::Slope s = test::slope(theta, mu, steps);
      const test::SlopeMotion m = run_slope(s);
      INFO("theta " << theta << " deg, mu " << mu << ", " << steps << " substeps: after " << kSeconds
                    << " s the furthest mass moved " << m.max_distance << " m; clearance " << m.min_clearance
                    << " .. " << m.max_clearance << " m");
      CHECK(m.max_distance < 1e-6);
      CHECK(m.min_clearance > 0.0);
      CHECK(m.max_clearance < 2e-4);
    }
  }
}

TEST_CASE("fabric: a cloth on a slope with tan theta > mu slides with g (sin theta - mu cos theta), within 5 %, "
          "at 15, 30 and 60 substeps",
          "[friction]") {
  for (auto [theta, mu] : {std::pair{35.0, 0.4}, std::pair{25.0, 0.4}, std::pair{30.0, 0.0}}) {
    const double want = test::sliding_acceleration(theta, mu);
    for (int steps : {15, 30, 60}) {
      const test::Slope s = test::slope(theta, mu, steps);
      const test::SlopeMotion m = run_slope(s);
      // From rest, n substeps of dt move a mass by a dt^2 (1 + 2 + ... + n) = a dt^2 n (n + 1) / 2:
      // a t^2 / 2, and 1/n more (the position update takes the substep's new displacement).
      const double n = kFrames * steps, dt = kSeconds / n;
      const double a = 2.0 * m.mean_down / (dt * dt * n * (n + 1.0));
      INFO("theta " << theta << " deg, mu " << mu << ", " << steps << " substeps: " << a << " m/s^2 down the slope, "
                    << "closed form " << want << " (" << 100.0 * (a / want - 1.0) << " %); clearance "
                    << m.min_clearance << " .. " << m.max_clearance << " m");
      CHECK(a == Approx(want).epsilon(0.05));
      CHECK(m.min_clearance > 0.0);
      CHECK(m.max_clearance < 2e-4);
    }
  }
}

// Coulomb friction of the fabric solver (docs/model.md, "Coulomb friction (fabric)"): a cloth on a
// plane tilted by theta holds when tan theta < mu and slides with g (sin theta - mu cos theta)
// when tan theta > mu, at 15, 30 and 60 substeps alike, on the CPU reference (float, the GPU's
// twin). tests/test_gpu_contact.cpp checks that the GPU gives the same floats.
#include <catch2/catch.hpp>

#include <algorithm>

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

TEST_CASE("fabric: a cloth on a slope with tan theta > mu slides with g (sin theta - mu cos theta), within 3 %, "
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
      CHECK(a == Approx(want).epsilon(0.03));  // issue 43 item 4 (measured: -0.3 to -2.4 %)
      CHECK(m.min_clearance > 0.0);
      CHECK(m.max_clearance < 2e-4);
    }
  }
}

// Issue 43 item 4 on a curved collider: a 25² cloth of 1 m (fabric density, no pins) dropped
// 5 cm onto a sphere of 0.2 m under its centre at friction 0.8 drapes and stays (the removed
// xpbd let it slide off by frame ~250; scripts/fabric-check's "sphere" check). In double its
// centre moves less than 1 cm between frames 90 and 300. In float (the GPU's numbers) the
// drape is not settled at frame 90: a fold drops at frames 120-180 (the lowest mass from 0.67 to
// 0.375 m) and the centre moves 28 mm, then nothing moves: so float is held to the item over
// frames 300..600, where friction alone keeps the draped cloth where it is (docs/solvers.md).
template <class R> glm::dvec3 drape_centre(CpuBackend<R>& cpu, int frames, double* nearest = nullptr) {
  for (int f = 0; f < frames; ++f) cpu.step_frame();
  glm::dvec3 c(0);
  const auto& pos = cpu.state().pos;
  if (nearest) *nearest = 1e9;
  for (const auto& p : pos) {
    const glm::dvec3 x(p.x, p.y, p.z);
    c += x / double(pos.size());
    if (nearest) *nearest = std::min(*nearest, glm::length(x - glm::dvec3(0.5, 0.75, 0.5)) - 0.2);
  }
  return c;
}

TEMPLATE_TEST_CASE("fabric: a cloth draped on a sphere at friction 0.8 stays on it", "[friction][long]", float, double) {
  const Scene s = test::sphere_drape(25, 0.8);
  const ClothModel m = build_cloth(s);
  CpuBackend<TestType> cpu(s, m);
  const bool single = sizeof(TestType) == 4;
  const int from = single ? 300 : 90, to = single ? 600 : 300;
  const glm::dvec3 a = drape_centre(cpu, from);
  double nearest = 0;
  const glm::dvec3 b = drape_centre(cpu, to - from, &nearest);
  const double moved = glm::length(b - a);
  INFO("centre moved " << moved * 1e3 << " mm over frames " << from << ".." << to << "; nearest mass " << nearest * 1e3
                       << " mm from the sphere");
  CHECK(moved < 0.01);
  CHECK(nearest < 0.01);  // still on it
  CHECK(a.y < 0.95);      // it did fall onto the sphere
}

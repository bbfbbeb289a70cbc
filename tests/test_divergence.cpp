// The divergence guard on the CPU: check_divergence and keep_last_good (the twins of the GPU
// passes), the one message both backends print, and the stress runs on the reference.
#include <catch2/catch.hpp>

#include <limits>

#include "backend.hpp"
#include "stress_cases.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

template <class R> std::vector<Vec4<R>> positions(std::initializer_list<Vec4<R>> p) { return p; }

const float kNaN = std::numeric_limits<float>::quiet_NaN(), kInf = std::numeric_limits<float>::infinity();

}  // namespace

TEMPLATE_TEST_CASE("check_divergence boxes the finite positions and flags a NaN or an Inf", "[divergence]", float,
                   double) {
  using R = TestType;
  const auto fine = positions<R>({{1, 2, 3, 1}, {-1, 5, 0.5, 0}, {0, -2, 4, 1}});
  ClothBounds b = check_divergence(fine);
  CHECK(b.finite);
  CHECK(b.lo == glm::vec3(-1, -2, 0.5));
  CHECK(b.hi == glm::vec3(1, 5, 4));
  for (R bad : {R(kNaN), R(kInf), -R(kInf)}) {
    auto p = fine;
    p[1].y = bad;
    b = check_divergence(p);
    CHECK_FALSE(b.finite);
    // The box holds the other, finite particles.
    CHECK(b.lo == glm::vec3(0, -2, 3));
    CHECK(b.hi == glm::vec3(1, 2, 4));
  }
}

TEST_CASE("a frame passes while the cloth stays within 1000 cloth sizes of where it started", "[divergence]") {
  const Scene s = test::make_scene(7, 5, 0);
  const ClothModel m = build_cloth(s);
  const DivergenceLimits l = divergence_limits(s, m);
  CHECK(l.centre == glm::vec3(0.5f, 1.f, 0.5f));
  CHECK(l.limit == 1000.f);
  ClothBounds b{true, glm::vec3(0.f, 1.f, 0.f), glm::vec3(1.f, 1.f, 1.f)};
  CHECK(within_limits(b, l));
  b.hi.y = 1001.f;  // exactly at the limit passes
  CHECK(within_limits(b, l));
  b.hi.y = std::nextafter(1001.f, 2000.f);
  CHECK_FALSE(within_limits(b, l));
  b.hi.y = 1.f;
  b.lo.x = -1000.f;
  CHECK_FALSE(within_limits(b, l));
  b.lo.x = 0.f;
  b.finite = false;
  CHECK_FALSE(within_limits(b, l));
}

TEST_CASE("the divergence message names the frame, what happened, the likely cause and what to change",
          "[divergence]") {
  Scene s = test::make_scene(7, 5, 0, {"cloth.ks=1e9"});
  const ClothModel m = build_cloth(s);
  CHECK_FALSE(divergence_message(s, m, {3, {true, glm::vec3(0), glm::vec3(1)}}).has_value());

  const auto nan = divergence_message(s, m, {12, {false, glm::vec3(0), glm::vec3(1)}});
  REQUIRE(nan.has_value());
  CHECK(*nan ==
        "the simulation diverged at frame 12: a particle position became NaN/Inf. Likely cause: the springs are too "
        "stiff for the time step (ks 1e+09 N/m on 4.29 kg particles needs substeps shorter than about 3.3e-05 s; "
        "these are 0.00037 s). Lower cloth.ks (now 1e+09; about 7.81e+06 is stable with these substeps) or raise "
        "simulation.simulation_steps (now 30, at most 100000), e.g. --set simulation.simulation_steps=340");

  const auto far = divergence_message(s, m, {7, {true, glm::vec3(0), glm::vec3(0.5f, 2501.f, 1.f)}});
  REQUIRE(far.has_value());
  CHECK_THAT(*far, Catch::StartsWith("the simulation diverged at frame 7: the cloth reached 2.5e+03 m from where it "
                                     "started (limit 1e+03 m). Likely cause: the springs are too stiff"));

  // With a time step that suits the springs, the advice is about the other extremes.
  s.cloth.ks = 5000;
  const auto other = divergence_message(s, m, {2, {false, glm::vec3(0), glm::vec3(1)}});
  REQUIRE(other.has_value());
  CHECK_THAT(*other, Catch::Contains("Likely cause: extreme parameters (cloth.ks 5000, cloth.density 150, "
                                     "simulation.gravity, colliders)"));
  CHECK_THAT(*other, Catch::EndsWith("--set simulation.simulation_steps=120"));
}

TEST_CASE("keep_last_good keeps the newest passing frame, and none after a failure", "[divergence]") {
  const Scene s = test::make_scene(7, 5, 0);
  const ClothModel m = build_cloth(s);
  const DivergenceLimits l = divergence_limits(s, m);
  KeptFrame<float> kept;
  const auto good = positions<float>({{0, 1, 0, 1}, {1, 1, 1, 1}});
  const auto bad = positions<float>({{0, 1, 0, 1}, {kNaN, 1, 1, 1}});
  keep_last_good(check_divergence(good), l, 1, good, kept);
  CHECK(kept.frame == 1);
  CHECK(kept.pos == good);
  keep_last_good(check_divergence(bad), l, 2, bad, kept);
  CHECK(kept.tripped);
  // A later frame that passes again (a cloth flung far that came back) is not kept either.
  keep_last_good(check_divergence(good), l, 3, good, kept);
  CHECK(kept.frame == 1);
}

TEMPLATE_TEST_CASE("the CPU backend checks every frame once and keeps the last good one", "[divergence]", float,
                   double) {
  const Scene s = test::make_scene(7, 5, 1, {"cloth.pinned=[[0,0],[6,0]]", "simulation.self_collision=false"});
  const ClothModel m = build_cloth(s);
  CpuBackend<TestType> cpu(s, m);
  int frame = -1;
  CHECK(test::max_abs_diff(cpu.last_good(&frame).pos, cpu.snapshot().pos) == 0);
  CHECK(frame == 0);
  for (int f = 1; f <= 3; ++f) {
    cpu.step_frame();
    const auto checks = cpu.take_checks(false);
    REQUIRE(checks.size() == 1);
    CHECK(checks[0].frame == f);
    CHECK_FALSE(divergence_message(s, m, checks[0]).has_value());
  }
  CHECK(cpu.take_checks(true).empty());
  CHECK(test::max_abs_diff(cpu.last_good(&frame).pos, cpu.snapshot().pos) == 0);
  CHECK(frame == 3);
}

namespace {

// Every case on the float and the double reference, with the checks the case itself implies.
template <class R> void run_cpu_stress(const std::string& name) {
  const test::StressCase c = test::stress_case(name);
  const Scene s = test::stress_scene(c);
  const ClothModel m = build_cloth(s);
  CpuBackend<R> cpu(s, m);
  const test::StressOutcome out = test::run_stress(cpu, s, m, c);
  test::check_stress_outcome(c, out);
  if (c.diverges) return;
  const ClothStats st = measure(s, m, out.last);
  CHECK(st.finite);
  // The cloth starts on both sides of that plane: it has no outside to measure from.
  if (name == "a plane through the cloth") return;
  // Contact tolerance: the friction blend and the length constraint run after the projection.
  for (double clearance : st.sphere_clearance) CHECK(clearance > -2e-3);
  for (double clearance : st.plane_clearance) CHECK(clearance > -2e-3);
}

}  // namespace

#define CPU_STRESS_TEST(NAME)                                                                               \
  TEMPLATE_TEST_CASE("10,000 substeps on the reference: " NAME, "[divergence][stress]", float, double) { \
    run_cpu_stress<TestType>(NAME);                                                                         \
  }

CPU_STRESS_TEST("stiff with enough substeps")
CPU_STRESS_TEST("far too stiff for its substeps")
CPU_STRESS_TEST("frictionless colliders")
CPU_STRESS_TEST("colliders with full friction")
CPU_STRESS_TEST("zero gravity, no damping")
CPU_STRESS_TEST("nothing pinned, self-collision on a plane")
CPU_STRESS_TEST("starting inside a sphere")
CPU_STRESS_TEST("a plane through the cloth")

TEST_CASE("10,000 substeps on the reference: everything pinned leaves every particle where it was", "[divergence][stress]") {
  const test::StressCase c = test::stress_case("everything pinned");
  const Scene s = test::stress_scene(c);
  const ClothModel m = build_cloth(s);
  CpuBackend<float> cpu(s, m);
  const test::StressOutcome out = test::run_stress(cpu, s, m, c);
  test::check_stress_outcome(c, out);
  const State<float> initial = initial_state<float>(m);
  for (int i = 0; i < m.count(); ++i) CHECK(glm::dvec4(initial.pos[i]) == out.last.pos[i]);
}

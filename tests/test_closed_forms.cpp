// Physics, not twins (issue 22 item 3), on the CPU reference in double and in float: a hanging
// chain stretches each link by the weight below it over ks, a chain started in its lowest mode
// swings at that mode's frequency, and a loaded sheet comes to rest where Newton's static solve
// puts it. The GPU twins are in test_gpu_closed_forms.cpp.
//
// fabric meets all three (the classic solver's chain and sheet: test_fidelity.cpp and the GPU tier).
#include <catch2/catch.hpp>

#include <cmath>

#include "backend.hpp"
#include "closed_form_cases.hpp"
#include "analysis/static_solve.hpp"

using namespace clothsim;

namespace {

template <class R> double chain_error(const std::string& solver) {
  const Scene s = test::hanging_chain(solver);
  const ClothModel m = build_cloth(s);
  CpuBackend<R> cpu(s, m);
  for (int f = 0; f < test::kRestFrames; ++f) cpu.step_frame();
  return test::chain_stretch_error(cpu.state().pos);
}

template <class R> double mode_omega(const std::string& solver, int* periods) {
  const Scene s = test::free_chain(solver);
  const ClothModel m = build_cloth(s);
  const Constants<R> c = make_constants<R>(s, m);
  State<R> st = initial_state<R>(m);
  test::stretch_into_mode(st.pos, test::kModeAmplitude);
  std::vector<double> u;  // the free end's displacement from rest (z = 0), every frame
  for (int f = 0; f < test::kModeFrames; ++f) {
    for (int k = 0; k < s.simulation.simulation_steps; ++k) step(m, c, st);
    u.push_back(test::chain_z(st.pos, 0, 0));
  }
  return test::measured_omega(u, 1.0 / s.simulation.frames_per_sec, periods);
}

template <class R> double sheet_error(const std::string& solver, double* sag) {
  const Scene s = test::loaded_sheet(solver);
  const ClothModel m = build_cloth(s);
  const StaticEquilibrium eq = solve_static_equilibrium(s, m);
  REQUIRE(eq.converged);
  *sag = 0;
  for (size_t i = 0; i < eq.pos.size(); ++i) *sag = std::max(*sag, m.initial[i].y - eq.pos[i].y);
  CpuBackend<R> cpu(s, m);
  for (int f = 0; f < test::kRestFrames; ++f) cpu.step_frame();
  return test::distance_from(cpu.state().pos, eq.pos);
}

}  // namespace

TEST_CASE("the static solve: a hanging chain's links stretch by the weight below over ks", "[closed-form]") {
  // The solve itself checked against the formula before anything is checked against it.
  const Scene s = test::hanging_chain("classic");
  const StaticEquilibrium eq = solve_static_equilibrium(s, build_cloth(s));
  INFO("Newton: " << eq.iterations << " steps, largest force left " << eq.residual << " N");
  REQUIRE(eq.converged);
  CHECK(test::chain_stretch_error(eq.pos) <= 1e-9);
}

TEST_CASE("the static solve refuses what it does not model", "[closed-form]") {
  for (const char* extra : {R"(, "plane": {"point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5})",
                            R"(, "wind": {"velocity": [1, 0, 0]})"}) {
    const Scene s = test::make_scene(5, 5, 0, {"simulation.self_collision=false"}, extra);
    CHECK_THROWS_AS(solve_static_equilibrium(s, build_cloth(s)), std::invalid_argument);
  }
}

TEMPLATE_TEST_CASE("classic: a hanging chain at rest stretches each link by the weight below it over ks, within 1 %",
                   "[closed-form]", float, double) {
  const double e = chain_error<TestType>("classic");
  INFO("largest relative error of a link's stretch: " << e);
  CHECK(e <= 0.01);
}

TEMPLATE_TEST_CASE("classic: a chain stretched into its lowest mode and released swings at its frequency, within 5 %",
                   "[closed-form]", float, double) {
  int periods = 0;
  const double omega = mode_omega<TestType>("classic", &periods);
  INFO("omega " << omega << " rad/s over " << periods << " periods; the mode's " << test::chain_mode_omega());
  CHECK(omega == Approx(test::chain_mode_omega()).epsilon(0.05));
}

TEMPLATE_TEST_CASE("classic: a sheet pinned along its border rests under its weight where the static solve puts it, "
                   "within 1 mm",
                   "[closed-form][long]", float, double) {
  double sag = 0;
  const double e = sheet_error<TestType>("classic", &sag);
  INFO("static sag " << sag << " m; largest distance from it after 300 frames " << e << " m");
  CHECK(sag > 0.01);  // a load the springs really carry
  CHECK(e <= 1e-3);
}

TEST_CASE("fabric: a chain at rest saved and resumed with twice the substeps stays at rest",
          "[closed-form][checkpoint]") {
  // The displacements are per substep and the solve's offsets (solve_start_offset) of the
  // substep before: loaded under half the substep length, the chain must not start moving.
  const Scene s = test::hanging_chain("fabric");
  const ClothModel m = build_cloth(s);
  CpuBackend<double> first(s, m);
  for (int f = 0; f < test::kRestFrames; ++f) first.step_frame();
  const SavedState saved = first.save_state();
  Scene finer = s;
  finer.simulation.simulation_steps = 2 * s.simulation.simulation_steps;
  CpuBackend<double> resumed(finer, m);
  resumed.load_state(saved);
  resumed.step_frame();
  const ClothStats st = measure(finer, m, resumed.snapshot());
  const double e = test::chain_stretch_error(resumed.state().pos);
  INFO("after one frame at 60 substeps: largest relative link error " << e << ", max speed " << st.max_speed << " m/s");
  CHECK(e <= 0.01);
  CHECK(st.max_speed <= 2e-5);  // 5e-6 m/s: what is left of the settling
}

// fabric solves implicit Euler itself, so its rest state is the static solve's whatever the
// stiffness, started where the last substep's acceleration says (solve_start_offset): at rest,
// where it rests.
TEST_CASE("fabric: a chain stretched into its lowest mode and released swings at its frequency, within 5 %",
          "[closed-form]") {
  const std::string solver = "fabric";
  int periods = 0;
  const double omega = mode_omega<double>(solver, &periods);
  INFO(solver << ": omega " << omega << " rad/s over " << periods << " periods; the mode's " << test::chain_mode_omega());
  CHECK(omega == Approx(test::chain_mode_omega()).epsilon(0.05));
}

TEMPLATE_TEST_CASE("fabric: a hanging chain at rest stretches each link by the weight below it over ks, within 1 %",
                   "[closed-form]", float, double) {
  const std::string solver = "fabric";
  const double e = chain_error<TestType>(solver);
  INFO(solver << ": largest relative error of a link's stretch: " << e);
  CHECK(e <= 0.01);
}

TEMPLATE_TEST_CASE("fabric: a sheet pinned along its border rests under its weight where the static solve "
                   "puts it, within 1 mm",
                   "[closed-form][long]", float, double) {
  const std::string solver = "fabric";
  double sag = 0;
  const double e = sheet_error<TestType>(solver, &sag);
  INFO(solver << ": static sag " << sag << " m; largest distance from it after 300 frames " << e << " m");
  CHECK(e <= 1e-3);
}

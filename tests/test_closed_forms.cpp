// Physics, not twins (issue 22 item 3), on the CPU reference in double and in float: a hanging
// chain stretches each link by the weight below it over ks, a chain started in its lowest mode
// swings at that mode's frequency, and a loaded sheet comes to rest where Newton's static solve
// puts it. The GPU twins are in test_gpu_closed_forms.cpp.
//
// Both solvers meet all three. xpbd did not before its multipliers were carried from substep to
// substep (docs/model.md, "Warm-started multipliers"): with lambda from 0 every substep its rest
// state was off by about 2 (ks/m) dt^2 per spring (2 % on the chain, 1.26 mm on the sheet's 5 cm
// sag), the bias that grows four-fold per doubling of the resolution.
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

TEST_CASE("xpbd: a chain stretched into its lowest mode and released swings at its frequency, within 5 %",
          "[closed-form]") {
  int periods = 0;
  const double omega = mode_omega<double>("xpbd", &periods);
  INFO("omega " << omega << " rad/s over " << periods << " periods; the mode's " << test::chain_mode_omega());
  CHECK(omega == Approx(test::chain_mode_omega()).epsilon(0.05));
}

TEMPLATE_TEST_CASE("xpbd: a hanging chain at rest stretches each link by the weight below it over ks, within 1 %",
                   "[closed-form]", float, double) {
  const double e = chain_error<TestType>("xpbd");
  INFO("largest relative error of a link's stretch: " << e << " (0.02 with lambda from 0 every substep)");
  CHECK(e <= 0.01);
}

TEMPLATE_TEST_CASE("xpbd: a sheet pinned along its border rests under its weight where the static solve puts it, "
                   "within 1 mm",
                   "[closed-form][long]", float, double) {
  double sag = 0;
  const double e = sheet_error<TestType>("xpbd", &sag);
  INFO("static sag " << sag << " m; largest distance from it after 300 frames " << e
                     << " m (1.26 mm with lambda from 0 every substep)");
  CHECK(e <= 1e-3);
}

TEST_CASE("xpbd: a chain at rest saved and resumed with twice the substeps stays at rest (multipliers rescaled)",
          "[closed-form][checkpoint]") {
  // The carried multipliers are forces times dt^2: loaded under half the substep length they
  // must shrink four-fold, or the first substep would pull every link with four times its force.
  const Scene s = test::hanging_chain("xpbd");
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
  // The control: the same resume with the multipliers put back to their saved size does kick.
  CpuBackend<double> unscaled(finer, m);
  unscaled.load_state(saved);
  for (auto& l : unscaled.state().lambda) l.w *= 4;
  unscaled.step_frame();
  const double kicked = measure(finer, m, unscaled.snapshot()).max_speed;
  INFO("the same with the multipliers unscaled: max speed " << kicked << " m/s");
  CHECK(kicked > 2e-5);  // 1.3e-4 m/s
}

// The multigrid solver solves implicit Euler itself, so its rest state is the static solve's
// whatever the stiffness: the same three checks. fabric is the same solve started where the
// last substep's acceleration says (solve_start_offset): at rest, where it rests, so the same.
TEST_CASE("multigrid and fabric: a chain stretched into its lowest mode and released swings at its frequency, within 5 %",
          "[closed-form]") {
  const std::string solver = GENERATE("multigrid", "fabric");
  int periods = 0;
  const double omega = mode_omega<double>(solver, &periods);
  INFO(solver << ": omega " << omega << " rad/s over " << periods << " periods; the mode's " << test::chain_mode_omega());
  CHECK(omega == Approx(test::chain_mode_omega()).epsilon(0.05));
}

TEMPLATE_TEST_CASE("multigrid and fabric: a hanging chain at rest stretches each link by the weight below it over ks, within 1 %",
                   "[closed-form]", float, double) {
  const std::string solver = GENERATE("multigrid", "fabric");
  const double e = chain_error<TestType>(solver);
  INFO(solver << ": largest relative error of a link's stretch: " << e);
  CHECK(e <= 0.01);
}

TEMPLATE_TEST_CASE("multigrid and fabric: a sheet pinned along its border rests under its weight where the static solve "
                   "puts it, within 1 mm",
                   "[closed-form][long]", float, double) {
  const std::string solver = GENERATE("multigrid", "fabric");
  double sag = 0;
  const double e = sheet_error<TestType>(solver, &sag);
  INFO(solver << ": static sag " << sag << " m; largest distance from it after 300 frames " << e << " m");
  CHECK(e <= 1e-3);
}

// The GPU twins of test_closed_forms.cpp (issue 22 item 3): the same closed forms checked on
// what the GPU computes (a hanging chain's link stretches, its lowest mode's frequency, a loaded
// sheet against Newton's static solve), and on llvmpipe the run bit for bit the float
// reference's. Both solvers.
#include <catch2/catch.hpp>

#include "closed_form_cases.hpp"
#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "pass_check.hpp"
#include "analysis/static_solve.hpp"

using namespace clothsim;

namespace {

// `frames` frames on the GPU from `start` (the model's initial state when empty), calling
// sample() after each, and on llvmpipe the same on the float reference, bit for bit at the end.
template <class Sample>
State<float> run_gpu(const Scene& s, const ClothModel& m, int frames, const State<float>* start, Sample&& sample) {
  GpuSimulator gpu(s, m, test::source_path("compute"));
  State<float> cpu = start ? *start : initial_state<float>(m);
  if (start) gpu.upload(*start);
  const Constants<float> c = make_constants<float>(s, m);
  const bool exact = gl::gl_renderer_is_llvmpipe();
  State<float> g;
  for (int f = 0; f < frames; ++f) {
    gpu.step_frame();
    if (exact)
      for (int k = 0; k < s.simulation.simulation_steps; ++k) step(m, c, cpu);
    gpu.download(g);
    sample(g);
  }
  if (exact) {
    const Deviation d = deviation(g.pos, cpu.pos);
    INFO("GPU - CPU (float) " << d.max << " m");
    CHECK(d.bitwise);
  }
  return g;
}

double gpu_chain_error(const std::string& solver) {
  const Scene s = test::hanging_chain(solver);
  const ClothModel m = build_cloth(s);
  return test::chain_stretch_error(run_gpu(s, m, test::kRestFrames, nullptr, [](const State<float>&) {}).pos);
}

double gpu_mode_omega(const std::string& solver, int* periods) {
  const Scene s = test::free_chain(solver);
  const ClothModel m = build_cloth(s);
  State<float> start = initial_state<float>(m);
  test::stretch_into_mode(start.pos, test::kModeAmplitude);
  std::vector<double> u;
  run_gpu(s, m, test::kModeFrames, &start, [&](const State<float>& g) { u.push_back(test::chain_z(g.pos, 0, 0)); });
  return test::measured_omega(u, 1.0 / s.simulation.frames_per_sec, periods);
}

double gpu_sheet_error(const std::string& solver) {
  const Scene s = test::loaded_sheet(solver);
  const ClothModel m = build_cloth(s);
  const StaticEquilibrium eq = solve_static_equilibrium(s, m);
  REQUIRE(eq.converged);
  return test::distance_from(run_gpu(s, m, test::kRestFrames, nullptr, [](const State<float>&) {}).pos, eq.pos);
}

}  // namespace

TEST_CASE("on the GPU a hanging chain's links stretch by the weight below over ks, within 1 %, every solver", "[gpu][long]") {
  REQUIRE_GL_CONTEXT();
  const std::string solver = GENERATE("classic", "fabric");
  const double e = gpu_chain_error(solver);
  INFO(solver << ": largest relative error of a link's stretch: " << e);
  CHECK(e <= 0.01);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("on the GPU a chain released from its lowest mode swings at its frequency, within 5 %, every solver",
          "[gpu][long]") {
  REQUIRE_GL_CONTEXT();
  const std::string solver = GENERATE("classic", "fabric");
  int periods = 0;
  const double omega = gpu_mode_omega(solver, &periods);
  INFO(solver << ": omega " << omega << " rad/s over " << periods << " periods; the mode's " << test::chain_mode_omega());
  CHECK(omega == Approx(test::chain_mode_omega()).epsilon(0.05));
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("on the GPU a sheet pinned along its border rests where the static solve puts it, within 1 mm, every solver",
          "[gpu][long]") {
  REQUIRE_GL_CONTEXT();
  const std::string solver = GENERATE("classic", "fabric");
  const double e = gpu_sheet_error(solver);
  INFO(solver << ": largest distance from the static solve after 300 frames " << e << " m");
  CHECK(e <= 1e-3);
  CHECK_NO_GL_ERRORS();
}

// Every compute pass of the GPU simulator against its CPU twin (docs/design.md §1, §6): each pass
// alone from an identical state, on a grid within one workgroup (7x5), one of a few (33x17)
// and one wider and taller than a workgroup (131x129); whole runs; pins; determinism; collider
// arrays; other settings. On llvmpipe the reference rounds exactly like the shaders, so
// "matches" means bit for bit there; on other GPUs (FMA, approximate sqrt and division) it
// means within the stated tolerances.
#include "gpu_pass_fixtures.hpp"

TEST_CASE("each GPU pass matches the reference from an identical state on a 7x5 cloth", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_passes_on_grid(7, 5);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("each GPU pass matches the reference from an identical state on a 33x17 cloth", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_passes_on_grid(33, 17);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("each GPU pass matches the reference from an identical state on a 131x129 cloth, "
          "wider and taller than a workgroup",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  static_assert(WORKGROUP_SIZE < 129, "the grid must be larger than a workgroup in both directions");
  check_passes_on_grid(131, 129);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the limit_speed pass (simulation.max_speed) matches its CPU twin, checked from its row", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  for (const char* solver : {"classic", "fabric"}) {
    const Scene scene = pass_fixtures::pressed_cloth(33, 17, {fmt::format("simulation.solver=\"{}\"", solver),
                                                              "simulation.max_speed=0.05"});
    const ClothModel model = build_cloth(scene);
    GpuSimulator gpu(scene, model, pass_fixtures::compute_dir());
    const std::vector<PassError> errors = check_passes(scene, model, gpu, pass_fixtures::kWarmupFrames);
    const auto it = std::find_if(errors.begin(), errors.end(), [](const PassError& e) { return e.pass == "limit_speed"; });
    REQUIRE(it != errors.end());
    INFO(solver << ": max |GPU - CPU| = " << it->max_error << " m");
    if (gl::gl_renderer_is_llvmpipe())
      CHECK(it->bitwise);
    else
      CHECK(it->max_error <= pass_fixtures::kPassTolerance);
  }
  CHECK_NO_GL_ERRORS();
}

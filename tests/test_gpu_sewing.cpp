// The GPU twin of tests/test_sewing.cpp: a panel sewn under a pinned one, with self-collision
// (the welds) and two cloths of different ks (the seam's lower ks), gives the reference's floats
// pass by pass and over a whole run, bit for bit on llvmpipe, on each solver that sews.
#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "gpu_pass_fixtures.hpp"
#include "sewing_fixtures.hpp"

TEST_CASE("sewn panels on the GPU: every pass and a whole run as the reference", "[gpu][sewing]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_sewing", "hang");
  for (const char* solver : {"classic", "fabric"}) {
    INFO(solver);
    const Scene s = parse_scene(test::hanging_panels_scene(dir, solver, 400, 200, true), dir / "sew.json");
    const ClothModel model = build_cloth(s);
    pass_fixtures::check_every_pass_alike(s, model, 6);
    GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
    CpuBackend<float> cpu(s, model);
    State<float> out;
    for (int f = 0; f < 30; ++f) gpu.step_frame(), cpu.step_frame();  // a third of a second: sewn at 0.1 s
    gpu.download(out);
    pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
    pass_fixtures::check_same("displacements", out.disp, cpu.state().disp, pass_fixtures::kRunTolerance);
  }
  CHECK_NO_GL_ERRORS();
}

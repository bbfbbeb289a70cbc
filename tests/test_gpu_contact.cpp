// The GPU twins of tests/test_contact_colliders.cpp: the new collider branches (a mass found
// behind a plane, a mass through a static sphere, a fast sphere over a mass) give the
// reference's floats bit for bit on llvmpipe.
#include "contact_cases.hpp"
#include "gpu_pass_fixtures.hpp"

TEST_CASE("collide_objects on the GPU lifts and catches exactly as the reference", "[gpu][contact]") {
  REQUIRE_GL_CONTEXT();
  const Scene s = test::contact_scene();
  const ClothModel m = build_cloth(s);
  GpuSimulator gpu(s, m, pass_fixtures::compute_dir());
  gpu.set_time(0.0);
  auto c = make_constants<float>(s, m);
  set_substep_time(c, 0.0);
  auto st = initial_state<float>(m);
  test::set_contact_state(st);
  gpu.upload(st);
  gpu.collide_objects();
  collide_objects(c, st);
  State<float> out;
  gpu.download(out);
  CHECK(st.pos[0].y > 0.5f);
  CHECK(st.pos[1].y > 0.8f);
  pass_fixtures::check_same("positions", out.pos, st.pos, pass_fixtures::kPassTolerance);
  pass_fixtures::check_same("displacements", out.disp, st.disp, pass_fixtures::kPassTolerance);
  CHECK_NO_GL_ERRORS();
}

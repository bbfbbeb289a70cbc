// The GPU twins of tests/test_contact_colliders.cpp: the new collider branches (a mass found
// behind a plane, a mass through a static sphere, a fast sphere over a mass) give the
// reference's floats bit for bit on llvmpipe; so does fabric's Coulomb friction on a slope.
#include "backend.hpp"
#include "contact_cases.hpp"
#include "friction_cases.hpp"
#include "gpu_pass_fixtures.hpp"
#include "mesh_collider_cases.hpp"

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
  gpu.run(PassId::collide_objects);
  collide_objects(c, st);
  State<float> out;
  gpu.download(out);
  CHECK(st.pos[0].y > 0.5f);
  CHECK(st.pos[1].y > 0.8f);
  pass_fixtures::check_same("positions", out.pos, st.pos, pass_fixtures::kPassTolerance);
  pass_fixtures::check_same("displacements", out.disp, st.disp, pass_fixtures::kPassTolerance);
  CHECK_NO_GL_ERRORS();
}

// fabric's Coulomb friction (tests/test_friction.cpp) on the GPU: a cloth sliding down a slope
// and one held on it give the reference's floats, each pass from an identical state and a
// whole run.
TEST_CASE("Coulomb friction on the GPU holds and slides a cloth on a slope exactly as the reference",
          "[gpu][contact][friction]") {
  REQUIRE_GL_CONTEXT();
  for (auto [theta, mu] : {std::pair{35.0, 0.4}, std::pair{20.0, 0.5}}) {
    INFO("theta " << theta << " deg, mu " << mu);
    const test::Slope s = test::slope(theta, mu, 30);
    {
      GpuSimulator gpu(s.scene, s.model, pass_fixtures::compute_dir());
      for (const PassError& e : check_passes(s.scene, s.model, gpu, 10)) {
        INFO(e.pass << ": max |GPU - CPU| = " << e.max_error << " m");
        if (gl::gl_renderer_is_llvmpipe()) CHECK(e.bitwise);
        else CHECK(e.max_error <= pass_fixtures::kPassTolerance);
      }
    }
    GpuSimulator gpu(s.scene, s.model, pass_fixtures::compute_dir());
    CpuBackend<float> cpu(s.scene, s.model);
    for (int f = 0; f < 20; ++f) {
      gpu.step_frame();
      cpu.step_frame();
    }
    State<float> out;
    gpu.download(out);
    const test::SlopeMotion moved = test::slope_motion(s, out.pos);
    INFO("moved " << moved.mean_down << " m down the slope in 20 frames");
    CHECK((theta > 30 ? moved.mean_down > 0.01 : moved.max_distance < 1e-6));
    pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
    pass_fixtures::check_same("displacements", out.disp, cpu.state().disp, pass_fixtures::kRunTolerance);
  }
  CHECK_NO_GL_ERRORS();
}

// The contact list (compute/contact_list.glsl): advance and predict list the masses a collider
// may move and collide_objects runs on those alone. From a state where the cloth is pressed
// between two spheres and two planes, or lies on a mesh collider, the first pass with the list
// gives what the same pass without collisions, then the reference's collide_objects on every
// mass, gives; every mass that collide_objects moves is listed, and masses far from every
// collider are not.
namespace {

void check_contact_list(const Scene& s, int warmup_frames, const std::string& solver) {
  const ClothModel m = build_cloth(s);
  GpuSimulator gpu(s, m, pass_fixtures::compute_dir());
  for (int f = 0; f < warmup_frames; ++f) gpu.step_frame();  // velocities, stretched springs, contacts
  State<float> start, without, with;
  gpu.download(start);
  auto first_pass = [&](bool then_collide) {
    gpu.upload(start);
    gpu.run(solver == "classic" ? PassId::advance : PassId::predict, {.collide_objects = then_collide});
  };
  first_pass(false);
  gpu.download(without);
  first_pass(true);
  gpu.download(with);
  const std::vector<uint32_t> listed = gpu.state().contact_list();
  auto c = make_constants<float>(s, m);
  State<float> expected = without;
  collide_objects(c, expected);
  pass_fixtures::check_same("positions", with.pos, expected.pos, pass_fixtures::kPassTolerance);
  pass_fixtures::check_same("displacements", with.disp, expected.disp, pass_fixtures::kPassTolerance);
  const size_t count = size_t(m.count());
  std::vector<int> times_listed(count, 0);
  for (uint32_t i : listed) {
    REQUIRE(i < count);
    ++times_listed[i];
  }
  size_t moved = 0, moved_unlisted = 0;
  for (size_t i = 0; i < count; ++i) {
    CHECK(times_listed[i] <= 1);
    const bool changed = !(expected.pos[i] == without.pos[i]) || !(expected.disp[i] == without.disp[i]);
    moved += changed;
    moved_unlisted += changed && times_listed[i] == 0;
  }
  INFO(listed.size() << " of " << count << " masses listed, " << moved << " moved by collide_objects");
  CHECK(moved > 0);
  CHECK(moved_unlisted == 0);
  CHECK(listed.size() >= moved);
  CHECK(listed.size() < count / 2);
  CHECK_NO_GL_ERRORS();
}

}  // namespace

TEST_CASE("the contact list holds every mass a collider moves, and colliding it alone is the reference's",
          "[gpu][contact]") {
  REQUIRE_GL_CONTEXT();
  for (const char* solver : {"classic", "fabric"}) {
    INFO(solver);
    check_contact_list(pass_fixtures::pressed_cloth(33, 17, {fmt::format("simulation.solver=\"{}\"", solver)},
                                                    pass_fixtures::kTwoSpheresTwoPlanes),
                       1, solver);
  }
}

// A mesh collider's early test (mesh_leaves_alone: outside its field's grid, or too far from its
// surface to have reached it) lists only the masses near the mesh: a 13² cloth, 1 m wide, lying
// on the icosphere and the torus of the mesh-collider tests.
TEST_CASE("the contact list holds every mass a mesh collider moves, and only masses near it", "[gpu][contact][long]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_contact_list", "meshes");
  for (const test::Shape& shape : test::shapes()) {
    if (shape.name == "cube") continue;
    const std::string obj = dir / (shape.name + ".obj");
    test::write_obj(shape.mesh, obj);
    for (const char* solver : {"classic", "fabric"}) {
      INFO(shape.name << ", " << solver);
      Scene s = test::drop_onto_mesh(obj, solver, "", {}, 1.0);
      check_contact_list(s, 45, solver);
    }
    // fabric's sweep decides whether a mass may need the push-out from the clearance bound
    // predict left in each displacement's w (mesh_leaves_alone_after), with no field sample:
    // the same sweep from the same prediction with the bound taken away (a state read back and
    // uploaded has w = 0, which takes every mass in the field's grid) gives the same bits.
    {
      INFO(shape.name << ", fabric's sweep");
      const Scene s = test::drop_onto_mesh(obj, "fabric", "", {}, 1.0);
      const ClothModel m = build_cloth(s);
      GpuSimulator gpu(s, m, pass_fixtures::compute_dir());
      for (int f = 0; f < 45; ++f) gpu.step_frame();
      State<float> start;
      gpu.download(start);
      auto sweep = [&](bool bound, State<float>& out) {
        gpu.upload(start);
        gpu.run(PassId::predict, {.collide_objects = true});
        if (!bound) {
          State<float> predicted;
          gpu.download(predicted);
          gpu.passes().download_multigrid(predicted);
          gpu.upload(predicted);
          gpu.passes().upload_multigrid(predicted);
        }
        gpu.passes().solve_multigrid();
        gpu.download(out);
      };
      State<float> with_bound, without;
      sweep(true, with_bound);
      sweep(false, without);
      CHECK(mismatches(with_bound.pos, without.pos) == 0);
      CHECK(mismatches(with_bound.disp, without.disp) == 0);
    }
  }
}

// Grabbing a particle on the GPU simulator: held where the mouse puts it, freed on release.
#include <catch2/catch.hpp>

#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "pass_check.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

TEST_CASE("a held particle stays where the mouse puts it and falls again once released", "[gpu][viewer]") {
  REQUIRE_GL_CONTEXT();
  Scene s = test::make_scene(7, 5, 0, {"simulation.self_collision=false", "simulation.simulation_steps=5"});
  ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, test::source_path("compute"));
  const int k = m.index(3, 2);
  const glm::vec3 target = glm::vec3(m.initial[k]) + glm::vec3(0.f, 0.05f, 0.f);  // a gentle lift
  State<float> st;
  for (int f = 0; f < 10; ++f) {
    sim.hold_particle(k, target);  // the viewer re-asserts the hold before every frame
    sim.step_frame();
    sim.download(st);
    CHECK(glm::vec3(st.pos[k]) == target);
    CHECK(st.pos[k].w == 0.f);
  }
  // Its neighbours are pulled up towards it while the rest of the cloth falls.
  CHECK(st.pos[m.index(3, 1)].y > st.pos[m.index(0, 0)].y);
  sim.release_particle(k);
  sim.download(st);
  CHECK(st.pos[k].w == Approx(1.0 / m.mass[k]));
  for (int f = 0; f < 30; ++f) sim.step_frame();
  sim.download(st);
  CHECK(st.pos[k].y < target.y - 0.01f);  // free again: it falls
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("reset puts the GPU cloth back to its initial state", "[gpu][viewer]") {
  REQUIRE_GL_CONTEXT();
  Scene s = test::make_scene(7, 5, 0, {"simulation.self_collision=false"});
  ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, test::source_path("compute"));
  for (int f = 0; f < 5; ++f) sim.step_frame();
  sim.reset();
  State<float> st;
  sim.download(st);
  const State<float> initial = initial_state<float>(m);
  CHECK(st.pos == initial.pos);
  CHECK(st.disp == initial.disp);  // at rest
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a live density change rescales the inverse masses in place", "[gpu][viewer]") {
  REQUIRE_GL_CONTEXT();
  Scene s = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0]]", "simulation.self_collision=false"});
  ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, test::source_path("compute"));
  s.cloth.density *= 2;
  sim.set_parameters(s);
  State<float> st;
  sim.download(st);
  CHECK(st.pos[0].w == 0.f);  // pinned stays pinned
  CHECK(st.pos[1].w == float(1.0 / (2 * m.mass[1])));
  CHECK(sim.constants().mass[1] == float(2 * m.mass[1]));
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a live change of the substep length keeps the GPU cloth's velocity, as on the reference", "[gpu][viewer]") {
  REQUIRE_GL_CONTEXT();
  Scene s = test::make_scene(7, 5, 0, {"simulation.self_collision=false", "cloth.pinned=[[0,0],[6,0]]"});
  ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, test::source_path("compute"));
  CpuBackend<float> cpu(s, m);
  for (int f = 0; f < 10; ++f) {
    sim.step_frame();
    cpu.step_frame();
  }
  State<float> before, after;
  sim.download(before);
  const double old_dt = s.dt();
  s = parse_scene(scene_to_json(s), "<test>", {"simulation.simulation_steps=70", "simulation.frames_per_sec=60"});
  sim.set_parameters(s);
  sim.download(after);
  const float ratio = float(s.dt() / old_dt);
  for (size_t i = 0; i < before.disp.size(); ++i) {
    INFO("particle " << i);
    // The same velocity d / dt: the displacement per substep scales with the substep.
    CHECK(after.disp[i].y == Approx(before.disp[i].y * ratio).epsilon(1e-6));
    CHECK(after.pos[i] == before.pos[i]);
  }
  // The reference's twin of the edit, then more frames on both: the same cloth.
  CpuBackend<float> edited(s, m);
  edited.state() = cpu.state();
  rescale_displacement(edited.state(), s.dt() / old_dt);
  for (int f = 0; f < 5; ++f) {
    sim.step_frame();
    edited.step_frame();
  }
  sim.download(after);
  const Deviation d = deviation(after.pos, edited.state().pos);
  INFO("GPU - CPU after the change: " << d.max << " m");
  if (gl::gl_renderer_is_llvmpipe()) CHECK(d.bitwise);
  CHECK(d.max < 1e-5);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a live edit that adds colliders compiles the passes for them and runs as the reference", "[gpu][viewer]") {
  REQUIRE_GL_CONTEXT();
  const std::vector<std::string> sets{"simulation.self_collision=false", "cloth.pinned=[[0,0],[6,0]]"};
  Scene s = test::make_scene(7, 5, 0, sets);
  ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, test::source_path("compute"));
  CpuBackend<float> cpu(s, m);
  // No collider: none of the collider code is in the passes (shader_features.hpp).
  CHECK(sim.passes().shader_features() == ShaderFeatures{false, false, false, false, false, false, false, false, false});
  for (int f = 0; f < 5; ++f) {
    sim.step_frame();
    cpu.step_frame();
  }
  // A sphere the falling cloth meets within a few frames, and a plane under it.
  Scene edited_scene = test::make_scene(
      7, 5, 0, sets,
      R"(, "sphere": {"origin": [0.5, 0.78, 0.4], "radius": 0.2, "friction": 0.3},)"
      R"( "plane": {"point": [0, 0.55, 0], "normal": [0, 1, 0], "friction": 0.5})");
  sim.set_parameters(edited_scene);
  CHECK(sim.passes().shader_features() == ShaderFeatures{true, true, false, false, false, false, false, false, false});
  CpuBackend<float> edited(edited_scene, m);
  edited.state() = cpu.state();
  for (int f = 0; f < 25; ++f) {
    sim.step_frame();
    edited.step_frame();
    cpu.step_frame();  // without the colliders
  }
  State<float> after;
  sim.download(after);
  // The colliders acted: the cloth is centimetres from where it goes without them.
  const double moved = deviation(edited.state().pos, cpu.state().pos).max;
  INFO("with the colliders - without: " << moved << " m");
  CHECK(moved > 0.01);
  const Deviation d = deviation(after.pos, edited.state().pos);
  INFO("GPU - CPU after the edit: " << d.max << " m");
  if (gl::gl_renderer_is_llvmpipe()) CHECK(d.bitwise);
  CHECK(d.max < 1e-5);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the passes compile in what each scene can reach, and no more", "[gpu][viewer]") {
  REQUIRE_GL_CONTEXT();  // (no GL call: kept with the GPU simulator's tests)
  auto features = [](const std::string& name, std::vector<std::string> sets = {}) {
    const Scene s = load_scene(test::source_path("scenes/" + name + ".json"), sets);
    return ShaderFeatures::of(make_constants<float>(s, build_cloth(s)));
  };
  // spheres, planes, meshes, a collider moves, Coulomb friction, pins move, wind, attachments, skinned
  CHECK(features("living") == ShaderFeatures{true, true, false, true, false, true, true, false, false});
  CHECK(features("pinned2") == ShaderFeatures{false, false, false, false, false, false, false, false, false});
  CHECK(features("hang_xpbd") == ShaderFeatures{false, false, false, false, true, false, false, false, false});
  CHECK(features("flag_pole") == ShaderFeatures{false, false, true, false, true, false, true, false, false});
  CHECK(features("cape") == ShaderFeatures{true, false, false, true, true, false, false, true, false});
}

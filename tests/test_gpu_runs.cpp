// Whole GPU runs against the reference: substeps in lock step, pins, determinism, several colliders, options.
#include "contact_cases.hpp"
#include "gpu_pass_fixtures.hpp"

TEST_CASE("50 GPU substeps match 50 reference substeps on a 33x17 cloth", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  SECTION("from the initial state the simulator uploads itself") { check_run(pressed_cloth(33, 17), 0, 50); }
  SECTION("from a state in contact with the sphere and the plane") {
    check_run(pressed_cloth(33, 17), kWarmupFrames, 50);
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("4 GPU substeps match 4 reference substeps on a 131x129 cloth in contact", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_run(pressed_cloth(131, 129), kWarmupFrames, 4);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("classic: masses found behind a plane and pulled behind it by Provot are kept out on the GPU as on the CPU",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  // Both plane keep-outs (after the blend, after Provot's pull) act from the first substep on.
  check_run(test::pin_behind_plane_scene(), 0, 60);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("pinned masses are bitwise unchanged after a GPU run, inside a sphere and on a plane too", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  // Pins at the two corners of the z = 0 edge and in the middle; the middle one sits inside
  // a small sphere, the (1, 1, 0) corner exactly on a plane, where both would move it.
  const Scene scene = test::make_scene(
      33, 17, 0, {"cloth.pinned=[[0,0],[32,0],[16,8]]", "simulation.self_collision=false"},
      R"(, "sphere": {"origin": [0.51, 1.0, 0.5], "radius": 0.05, "friction": 0.3},
           "plane": {"point": [1.0, 0.0, 0.0], "normal": [1.0, 0.0, 0.0], "friction": 0.5})");
  const ClothModel model = build_cloth(scene);
  const State<float> initial = initial_state<float>(model);
  GpuSimulator gpu(scene, model, compute_dir());
  for (int f = 0; f < 2; ++f) gpu.step_frame();
  State<float> g;
  gpu.download(g);
  const std::vector<int> pins = {model.index(0, 0), model.index(32, 0), model.index(16, 8)};
  for (int i : pins) {
    INFO("pinned particle " << i);
    CHECK(initial.pos[i].w == 0.f);
    CHECK(std::memcmp(&g.pos[i], &initial.pos[i], sizeof(g.pos[i])) == 0);
    CHECK(std::memcmp(&g.disp[i], &initial.disp[i], sizeof(g.disp[i])) == 0);
  }
  CHECK(moved(initial.pos, g.pos).all == initial.pos.size() - pins.size());  // everything else moved
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("two GPU runs from the same scene give bitwise identical buffers", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const Scene scene = pressed_cloth(33, 17);
  const ClothModel model = build_cloth(scene);
  State<float> runs[2];
  for (State<float>& run : runs) {
    GpuSimulator gpu(scene, model, compute_dir());
    for (int f = 0; f < kWarmupFrames + 1; ++f) gpu.step_frame();
    gpu.download(run);
  }
  CHECK(mismatches(runs[0].pos, runs[1].pos) == 0);
  CHECK(mismatches(runs[0].disp, runs[1].disp) == 0);
  CHECK(mismatches(runs[0].force, runs[1].force) == 0);
  CHECK(mismatches(runs[0].normal, runs[1].normal) == 0);
  CHECK(moved(initial_state<float>(model).pos, runs[0].pos).all > 0);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a second sphere and a second plane act on the GPU as on the CPU", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const Scene scene = pressed_cloth(33, 17, {}, kTwoSpheresTwoPlanes);
  check_exercised(scene, build_cloth(scene), kWarmupFrames, false);
  check_each_pass(scene, kWarmupFrames);
  const int warmup = kWarmupFrames - 1, substeps = 50;
  check_run(scene, warmup, substeps);
  // Each collider changes that run on the CPU, so a GPU that skipped one would not match.
  CpuCloth all(scene, warmup);
  all.run(substeps);
  for (int k = 0; k < 4; ++k) {
    CpuCloth without(scene, warmup);
    if (k < 2)
      without.c.control.spheres.erase(without.c.control.spheres.begin() + k);
    else
      without.c.control.planes.erase(without.c.control.planes.begin() + (k - 2));
    without.run(substeps);
    INFO((k < 2 ? "sphere " : "plane ") << k % 2);
    CHECK(moved(all.s.pos, without.s.pos).all > 0);
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the GPU matches the reference with spring types off, more constraint iterations, "
          "no damping, no colliders, or a vertical cloth",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  struct Variant {
    const char* name;
    std::vector<std::string> sets;
    const char* colliders = kSphereAndPlane;
    int orientation = 0;
  };
  const Variant v = GENERATE(values<Variant>({
      {"bending springs off", {"cloth.enable_bending=false"}},
      {"shearing springs off", {"cloth.enable_shearing=false"}},
      {"only bending springs", {"cloth.enable_structural=false", "cloth.enable_shearing=false"}},
      {"three constraint iterations, max_stretch 0.02",
       {"simulation.constraint_iterations=3", "simulation.max_stretch=0.02"}},
      {"no damping, sideways gravity", {"cloth.damping=0", "simulation.gravity=[1.5, -9.8, 2.5]"}},
      {"no colliders", {}, ""},
      {"vertical cloth",
       {},
       R"(, "sphere": {"origin": [0.5, 0.5, 0.1], "radius": 0.15, "friction": 0.2},
            "plane": {"point": [0.0, 0.3, 0.0], "normal": [0.0, 1.0, 0.0], "friction": 0.5})",
       1},
  }));
  INFO(v.name);
  const Scene scene = pressed_cloth(17, 11, v.sets, v.colliders, v.orientation);
  check_each_pass(scene, kWarmupFrames);
  check_run(scene, kWarmupFrames, 30);
  CHECK_NO_GL_ERRORS();
}

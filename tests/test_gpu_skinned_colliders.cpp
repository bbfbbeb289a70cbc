// The GPU twin of tests/test_skinned_colliders.cpp: a cloth on a skinned box that rises, slides
// and turns gives the reference's floats pass by pass (skin_colliders and fit_collider_boxes
// among them) and over a whole run, bit for bit on llvmpipe, on each solver.
#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "gpu_pass_fixtures.hpp"
#include "skinned_fixtures.hpp"

TEST_CASE("skinned colliders on the GPU: the skinning, every pass and a whole ride as the reference",
          "[gpu][skinned][long]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_skinned", "ride");
  const glm::quat turn = glm::angleAxis(0.3f, glm::vec3(0, 1, 0));
  const std::string file = test::write_skinned_box(
      dir.path, "box", 0.1f, {{0.f, 0.1f, 0.4f}, {}, {glm::quat(1, 0, 0, 0), glm::quat(1, 0, 0, 0), turn}});
  // fabric twice: the second with the cloth's corner attached to the box (it follows a skinned vertex).
  for (const char* solver : {"classic", "fabric", "fabric+attached"}) {
    INFO(solver);
    const bool attached = std::string(solver) == "fabric+attached";
    const Scene s = parse_scene(fmt::format(R"({{
      "cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5, "num_height_points": 5, "thickness": 0.004,
                 "orientation": 0, "density": 0.15, "ks": 500, "damping": 0.5{}}},
      "mesh": {{"file": "{}", "origin": [0.05, 0.9, 0.05], "friction": 0.5, "thickness": 0.004, "animation": 0,
                "motion": {{"keyframes": [[0, [0.05, 0.9, 0.05]], [0.4, [0.05, 0.95, 0.07]]]}}}},
      "simulation": {{"solver": "{}", "self_collision": false}}
    }})", attached ? R"(, "attachments": [{"collider": "mesh", "vertices": [0, 4], "stiffness": 50}])" : "", file,
                                attached ? "fabric" : solver), dir / "scene.json");
    const ClothModel model = build_cloth(s);
    pass_fixtures::check_every_pass_alike(s, model, 12);
    GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
    CpuBackend<float> cpu(s, model);
    State<float> out;
    for (int f = 0; f < 45; ++f) gpu.step_frame(), cpu.step_frame();
    gpu.download(out);
    pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
    pass_fixtures::check_same("displacements", out.disp, cpu.state().disp, pass_fixtures::kRunTolerance);
    pass_fixtures::check_same("skinned vertices and boxes", gpu.state().download_skinned(), cpu.constants().control.skinned,
                              pass_fixtures::kRunTolerance);
  }
  CHECK_NO_GL_ERRORS();
}

// Far records (compute/nearest.glsl): predict leaves alone, without a walk of the tree, a mass
// whose last walk or search bounded its distance to every triangle well beyond its reach, for as
// long as the two have not moved together by the difference. Here the box rises at 2 m/s into a
// falling cloth that starts 0.15 m above it, so every record is made far and runs out as the
// box comes: a bound that left out the surface's moves would let the box through the cloth,
// where the reference (which searches every mass) holds it.
TEST_CASE("skinned colliders on the GPU: a box that rises fast into a far cloth meets it as the reference",
          "[gpu][skinned]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_skinned", "far");
  const std::string file = test::write_skinned_box(dir.path, "box", 0.1f, {{0.f, 0.15f}, {{0, 0, 0}, {0, 0.3f, 0}}, {}});
  const Scene s = parse_scene(fmt::format(R"({{
    "cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5, "num_height_points": 5, "thickness": 0.004,
               "orientation": 0, "density": 0.15, "ks": 500, "damping": 0.5}},
    "mesh": {{"file": "{}", "origin": [0.05, 0.75, 0.05], "friction": 0.5, "thickness": 0.004, "animation": 0,
              "loop": false}},
    "simulation": {{"solver": "fabric", "self_collision": false}}
  }})", file), dir / "scene.json");
  const ClothModel model = build_cloth(s);
  GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
  CpuBackend<float> cpu(s, model);
  State<float> out;
  for (int f = 0; f < 30; ++f) gpu.step_frame(), cpu.step_frame();
  gpu.download(out);
  pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
  // The box carried the cloth up: it rests on the top, 1.05 + its thickness, not fallen through.
  for (const auto& p : out.pos) CHECK(p.y > 1.04f);
  CHECK_NO_GL_ERRORS();
}

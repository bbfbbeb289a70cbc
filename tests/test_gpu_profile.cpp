// simulate --profile on the GPU: the step's stage rows (the skinning among them), the contact
// list's collide_objects dispatches on rows of their own, and a profiled run (a glFinish around
// every pass) the same bits as one that is not.
#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "gpu_pass_fixtures.hpp"
#include "skinned_fixtures.hpp"

TEST_CASE("the GPU profiled times every stage and the contact list's dispatches and gives the same bits",
          "[gpu][profile]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_profile", "ride");
  const std::string file = test::write_skinned_box(dir.path, "box", 0.1f, {{0.f, 0.4f}, {{0, 0, 0}, {0, 0.05f, 0}}, {}});
  const Scene s = parse_scene(fmt::format(R"({{
    "cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5, "num_height_points": 5, "thickness": 0.004,
               "orientation": 0, "density": 0.15, "ks": 500, "damping": 0.5}},
    "mesh": {{"file": "{}", "origin": [0.05, 0.9, 0.05], "friction": 0.5, "thickness": 0.004, "animation": 0}},
    "simulation": {{"solver": "fabric", "self_collision": false}}
  }})", file), dir / "scene.json");
  const ClothModel model = build_cloth(s);
  GpuSimulator plain(s, model, pass_fixtures::compute_dir()), timed(s, model, pass_fixtures::compute_dir());
  PassProfile p;
  timed.set_profile(&p);
  constexpr int kFrames = 5;
  for (int f = 0; f < kFrames; ++f) plain.step_frame(), timed.step_frame();
  timed.set_profile(nullptr);
  State<float> a, b;
  plain.download(a);
  timed.download(b);
  pass_fixtures::check_same("positions", b.pos, a.pos, 0.0);
  pass_fixtures::check_same("displacements", b.disp, a.disp, 0.0);
  const int64_t substeps = int64_t(kFrames) * s.simulation.simulation_steps;
  auto runs_of = [&](const std::string& name) -> int64_t {
    for (const PassProfile::Row& r : p.rows())
      if (r.name == name) return r.runs;
    return 0;
  };
  for (const char* name : {"substep control", "skin_colliders", "fit_collider_boxes", "predict",
                           "collide_objects (first)", "compute_residuals", "cycle_levels", "prolong_to_cloth",
                           "relax_vertices"}) {
    INFO(name);
    CHECK(runs_of(name) == substeps);
  }
  CHECK(runs_of("compute_normals") == kFrames);
  CHECK(runs_of("check_divergence") == kFrames);
  CHECK_NO_GL_ERRORS();
}

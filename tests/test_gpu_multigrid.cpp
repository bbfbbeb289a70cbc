// The fabric solver's multigrid solve on the GPU (issue 22, 43; docs/model.md): each of its passes against its
// CPU twin from an identical state (bit for bit on llvmpipe), on a grid with two coarse levels
// and on the two-cloth mesh scene (self-collision, a sphere), and whole runs in lock step.
// The physics checks (closed forms) run in test_gpu_closed_forms.cpp.
#include "gpu_pass_fixtures.hpp"

namespace {

void check_multigrid_passes(const Scene& scene, int warmup) {
  const ClothModel model = build_cloth(scene);
  GpuSimulator gpu(scene, model, compute_dir());
  const std::vector<PassError> errors = check_passes(scene, model, gpu, warmup);
  int multigrid_passes = 0;
  for (const PassError& e : errors) {
    INFO(e.pass << ": max |GPU - CPU| = " << e.max_error << " m" << (e.bitwise ? " (bitwise equal)" : ""));
    if (gl::gl_renderer_is_llvmpipe()) CHECK(e.bitwise);
    else CHECK(e.max_error <= kPassTolerance);
    for (const char* pass : {"compute_residuals", "restrict_residuals", "cycle_small_levels", "prolong_corrections",
                             "smooth_corrections", "prolong_to_cloth", "relax_vertices"})
      multigrid_passes += e.pass.rfind(pass, 0) == 0;
  }
  // Every pass of the cycle was checked: one restriction per level, one prolongation and one
  // smoothing per level but the coarsest.
  const int levels = int(gpu.constants().hierarchy->levels.size());
  REQUIRE(levels >= 2);
  CHECK(multigrid_passes == 1 + levels + 1 + 2 * (levels - 1) + 1 + 1);
}

}  // namespace

TEST_CASE("each fabric pass matches the reference from an identical state on a 33x17 cloth (two coarse levels)",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_multigrid_passes(pressed_cloth(33, 17, {"simulation.solver=\"fabric\""}), kWarmupFrames);
  CHECK_NO_GL_ERRORS();
}

// fabric's adaptive start and fold threshold take their other branch where a mass is stiff for
// its inertia (adaptive_share, folded_chord_at: rho = ks dt^2 / m above kAdaptiveStartRho).
TEST_CASE("each fabric pass matches the reference on a 33x17 cloth stiff for its masses (rho above the start's bound)",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const Scene scene = pressed_cloth(33, 17, {"simulation.solver=\"fabric\"", "cloth.ks=3e9"});
  const ClothModel model = build_cloth(scene);
  const Constants<float> c = make_constants<float>(scene, model);
  REQUIRE(double(c.particle_ks[0]) * double(c.dt2) / double(c.mass[0]) > 4 * kAdaptiveStartRho);
  check_multigrid_passes(scene, kWarmupFrames);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("each fabric pass matches the reference on the two-cloth mesh scene (self-collision, a sphere)", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_multigrid_passes(load_scene(test::source_path("scenes/two_cloths.json"), {"simulation.solver=\"fabric\""}), 2);
  CHECK_NO_GL_ERRORS();
}

// A first coarse level over kSmallLevelVertices (2,401 vertices): its passes are dispatched
// one by one, the levels below it in cycle_small_levels' single dispatch.
TEST_CASE("each fabric pass matches the reference on a 97x95 cloth (a large level, then the small ones in one dispatch)",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const Scene scene = pressed_cloth(97, 95, {"simulation.solver=\"fabric\""});
  const ClothModel model = build_cloth(scene);
  REQUIRE(first_small_level(build_hierarchy(model, {scene.cloth.ks})) == 1);
  check_multigrid_passes(scene, 1);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a fabric run on the GPU follows the reference frame by frame, and counts its dispatches", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const Scene scene = pressed_cloth(33, 17, {"simulation.solver=\"fabric\""}, kTwoSpheresTwoPlanes);
  const ClothModel model = build_cloth(scene);
  GpuSimulator gpu(scene, model, compute_dir());
  CpuBackend<float> cpu(scene, model);
  const GpuCounters before = gpu.passes().counters();
  gpu.step_frame();
  const GpuCounters after = gpu.passes().counters();
  // Its two coarse levels are both small (kSmallLevelVertices): the whole V-cycle is one
  // dispatch, with compute_residuals, prolong_to_cloth and a dispatch per colour of the sweep,
  // each with its push-out inline (spheres and planes, no mesh: no dispatch of the contact list).
  CHECK(gpu.passes().multigrid_dispatches() == 3 + gpu.constants().hierarchy->fine_colours());
  // The substeps' dispatches, then the frame's own: normals and the divergence guard's two.
  CHECK(uint64_t(after.dispatches - before.dispatches) ==
        uint64_t(scene.simulation.simulation_steps * gpu.passes().dispatches_per_substep() + 3));
  cpu.step_frame();
  for (int f = 1; f < 4; ++f) {
    gpu.step_frame();
    cpu.step_frame();
  }
  State<float> g;
  gpu.download(g);
  check_same("positions after 4 frames", g.pos, cpu.state().pos, kRunTolerance);
  check_same("displacements after 4 frames", g.disp, cpu.state().disp, kRunTolerance);
  CHECK_NO_GL_ERRORS();
}

// A material's membrane and bending terms (docs/materials.md) in the sweep and the residuals, and
// its hinges' weight in the coarse problem: on a grid (its plate stencils) and on a mesh with
// self-collision and a sphere (its hinges).
TEST_CASE("each fabric pass matches the reference on cloths with a material (a grid's stencils, a mesh's hinges)",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_multigrid_passes(pressed_cloth(33, 17, {"simulation.solver=\"fabric\"", "cloth.material=\"denim\""}), kWarmupFrames);
  const std::string mesh = test::source_path("scenes/meshes/disc_hole.obj").string();
  const Scene disc = parse_scene(fmt::format(R"({{"cloth": {{"mesh": "{}", "scale": 0.8, "offset": [0.4, 1.1, 0.4],
      "rotation_axis": [0, 0, 1], "rotation_degrees": 20, "thickness": 0.008, "material": "silk"}},
      "sphere": {{"origin": [0.4, 0.8, 0.4], "radius": 0.2, "friction": 0.5}},
      "simulation": {{"solver": "fabric", "self_collision": true}}}})", mesh), "<disc>");
  check_multigrid_passes(disc, 2);
  CHECK_NO_GL_ERRORS();
}

// fabric's bounded self-contact on the GPU (docs/model.md, "Self-contact that holds"): the pass
// on a folded cloth against the reference, and whole heaps that end with no intersecting
// triangles (the exact counter of host/core/analysis/intersections.cpp, every tenth frame), bitwise the
// reference's on llvmpipe. The CPU side is test_self_contact.cpp.
#include "gpu_self_collision_fixtures.hpp"

TEST_CASE("the GPU's bounded contact equals the reference's on a cloth folded onto itself", "[gpu][self_contact]") {
  REQUIRE_GL_CONTEXT();
  // 33x17 over 0.4 m (spacing 12.5 mm along x, 25 mm along z, contact 20 mm): rows 9..16
  // folded back over rows 7..0, 12 mm above them, and squeezed along x to 10 mm apart, so
  // touching pairs are both across the fold and the cloth's own neighbours (kept at rest).
  Placed t(test::make_scene(33, 17, 0, {"cloth.width=0.4", "cloth.height=0.4", "cloth.thickness=0.01",
                                         "simulation.solver=\"fabric\"",
                                         "simulation.self_collision=true"}));
  REQUIRE(t.c.bounded_contact);
  t.fold_33x17(0.012f, 0.010f, 0.4f / 16, 5);
  const Positions before = t.s.pos;
  const Positions gpu = t.collide();
  check_same_pass_result(gpu, t.s.pos);
  int across = 0, neighbours = 0;
  for (int i = 0; i < t.model.count(); ++i)
    for (int j = i + 1; j < t.model.count(); ++j) {
      if (length3(Vec3<float>(before[i]) - Vec3<float>(before[j])) >= t.c.contact_distance) continue;
      (length3(t.c.rest[i] - t.c.rest[j]) < t.c.contact_distance ? neighbours : across) += 1;
    }
  INFO(across << " pairs across the fold, " << neighbours << " neighbour pairs closer than their rest distance");
  CHECK(across > 8 * 33);
  CHECK(neighbours > 16 * 32);
  CHECK(mismatches(before, t.s.pos) > size_t(t.model.count()) * 3 / 4);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a 65 x 65 heap on the GPU has no intersecting triangles at any tenth frame to 300, bitwise the reference's",
          "[gpu][self_contact][slow]") {
  REQUIRE_GL_CONTEXT();
  // heap256 on a 65 x 65 grid, thickness half the spacing (the contact distance one step). With
  // the CS184 contact it ends with 164 intersecting pairs at frame 70 (docs/model.md).
  const Scene scene = load_scene(test::source_path("scenes/heap256.json"),
                                 {"cloth.num_width_points=65", "cloth.num_height_points=65", "cloth.thickness=0.0078125"});
  const ClothModel model = build_cloth(scene);
  GpuSimulator gpu(scene, model, compute_dir());
  CpuBackend<float> cpu(scene, model);
  size_t worst = 0;
  State<float> s;
  for (int f = 1; f <= 300; ++f) {
    gpu.step_frame();
    if (f <= 30) cpu.step_frame();
    if (f == 30 && gl::gl_renderer_is_llvmpipe()) {
      gpu.download(s);
      const ClothSnapshot ref = cpu.snapshot();
      size_t differ = 0;
      for (size_t i = 0; i < s.pos.size(); ++i)
        differ += float(ref.pos[i].x) != s.pos[i].x || float(ref.pos[i].y) != s.pos[i].y || float(ref.pos[i].z) != s.pos[i].z;
      CHECK(differ == 0);
    }
    if (f % 10) continue;
    gpu.download(s);
    worst = std::max(worst, intersections_of(model, s));
  }
  float top = -1e9f;
  for (auto& p : s.pos) top = std::max(top, p.y);
  INFO("most intersecting pairs " << worst << "; heap top " << top << " m");
  CHECK(worst == 0);
  CHECK(top < 0.2f);
  CHECK_NO_GL_ERRORS();
}

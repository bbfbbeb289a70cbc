// GPU hashed-grid self-collision (docs/design.md §1 step 3) against the CPU reference: the push-out
// on a folded cloth, determinism of whole runs, and the heap of the classic scene. The hash
// stages themselves are tested in test_gpu_hash.cpp.
#include "gpu_self_collision_fixtures.hpp"

TEST_CASE("the GPU correction equals the reference's on a cloth folded onto itself", "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // 33x17 over 0.4 m: rows 9..16 folded back over rows 7..0, 0.6 thickness above them.
  Placed t(test::make_scene(33, 17, 0, {"cloth.width=0.4", "cloth.height=0.4"}));
  t.fold_33x17(0.6f * float(t.scene.cloth.thickness), 0.4f / 32, 0.4f / 16, 11);
  const Positions before = t.s.pos;
  const Positions gpu = t.collide();
  check_same_pass_result(gpu, t.s.pos);
  const size_t in_contact = mismatches(before, t.s.pos);  // particles the pass moved
  int across = 0;  // contact pairs between the two layers (within a layer x neighbours touch too)
  for (int i = 0; i < 9 * 33; ++i)
    for (int j = 9 * 33; j < t.model.count(); ++j)
      across += length3(Vec3<float>(before[i]) - Vec3<float>(before[j])) < t.c.contact_distance;
  WARN("folded cloth: " << in_contact << " of " << t.model.count() << " particles in contact, " << across
                        << " pairs across the fold; max |GPU - CPU| = " << max_diff(gpu, t.s.pos) << " m");
  CHECK(in_contact > size_t(t.model.count()) * 3 / 4);
  CHECK(across > 8 * 33);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("two GPU runs with self-collision are bitwise identical, and equal the reference on llvmpipe",
          "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // The selfCollision scene on a 17x17 grid: thickness scaled with the spacing (0.0095 * 49/16).
  const Scene scene = test::make_scene(17, 17, 1, {"cloth.thickness=0.0291"},
                                       R"(, "plane": {"point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5})");
  const ClothModel model = build_cloth(scene);
  const int substeps = 300;
  auto run_gpu = [&] {
    GpuSimulator gpu(scene, model, compute_dir());
    for (int k = 0; k < substeps; ++k) gpu.step();
    State<float> s;
    gpu.download(s);
    return s;
  };
  const State<float> a = run_gpu(), b = run_gpu();
  CHECK(mismatches(a.pos, b.pos) + mismatches(a.disp, b.disp) == 0);
  // The reference, pass by pass, counting the substeps in which self-collision moved something.
  const Constants<float> c = make_constants<float>(scene, model);
  State<float> s = initial_state<float>(model);
  int contact_steps = 0;
  for (int k = 0; k < substeps; ++k) {
    accumulate_forces(model, c, s);
    integrate(model, c, s);
    const Positions before = s.pos;
    collide_self(c, s);
    contact_steps += mismatches(before, s.pos) > 0;
    collide_objects(c, s);
    solve_length_constraints(model, c, s);
  }
  INFO(contact_steps << " of " << substeps << " substeps had self-contacts; max |GPU - CPU| = "
                     << max_diff(a.pos, s.pos) << " m");
  CHECK(contact_steps > substeps / 4);
  if (gl::gl_renderer_is_llvmpipe()) CHECK(mismatches(a.pos, s.pos) + mismatches(a.disp, s.disp) == 0);
  CHECK_NO_GL_ERRORS();
}

namespace {

// After 200 frames of selfCollision: fallen into a heap, no non-neighbours closer than the
// thickness. Pairs further than 2 grid steps apart in x or y share no spring.
void check_heap_spacing(const Scene& scene, const ClothModel& model, const State<float>& s) {
  const float thickness = float(scene.cloth.thickness);
  float closest = INFINITY, top = -INFINITY;
  int too_close = 0;
  for (int i = 0; i < model.count(); ++i) {
    top = std::max(top, s.pos[i].y);
    for (int j = i + 1; j < model.count(); ++j) {
      if (std::abs(i % model.nw - j % model.nw) <= 2 && std::abs(i / model.nw - j / model.nw) <= 2) continue;
      const float d = length3(Vec3<float>(s.pos[i]) - Vec3<float>(s.pos[j]));
      closest = std::min(closest, d);
      too_close += d < thickness;
    }
  }
  WARN("selfCollision after 200 frames: closest non-neighbours " << closest << " m (thickness " << thickness
                                                                 << " m), heap top at y = " << top << " m");
  CHECK(std::isfinite(closest));
  CHECK(top < 0.25f);  // it has fallen into a heap
  CHECK(too_close == 0);
}

}  // namespace

TEST_CASE("the selfCollision cloth heaps on the plane without non-neighbours closer than the thickness, "
          "and without intersecting triangles at any tenth frame to 300",
          "[gpu][self_collision][long]") {
  REQUIRE_GL_CONTEXT();
  // The classic scene as shipped: 50x50, 300 frames (9000 substeps; about 40 s on llvmpipe).
  const Scene scene = load_scene(test::source_path("scenes/selfCollision.json"));
  const ClothModel model = build_cloth(scene);
  GpuSimulator gpu(scene, model, compute_dir());
  State<float> s;
  size_t most_intersecting = 0;
  for (int f = 1; f <= 300; ++f) {
    gpu.step_frame();
    if (f % 10 && f != 200) continue;
    gpu.download(s);
    most_intersecting = std::max(most_intersecting, intersections_of(model, s));
    if (f == 200) check_heap_spacing(scene, model, s);
  }
  INFO("most intersecting triangle pairs at a tenth frame: " << most_intersecting);
  CHECK(most_intersecting == 0);
  CHECK_NO_GL_ERRORS();
}

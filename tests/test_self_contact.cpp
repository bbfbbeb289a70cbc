// fabric's bounded self-contact (docs/model.md, "Self-contact that holds") on the CPU reference:
// the pair rule (contact distance, or the rest distance for the cloth's own neighbours), the
// speed limit of predict, and whole heaps that end with no intersecting triangles, checked by
// the exact counter of host/core/analysis/intersections.cpp every tenth frame. The GPU twin is
// test_gpu_self_contact.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include "backend.hpp"
#include "analysis/intersections.hpp"
#include "reference/reference.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

std::filesystem::path shipped(const char* scene) { return std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "scenes" / scene; }

// heap256 (a vertical 1 m cloth collapsing onto the floor, fabric, self-collision) on an n x n
// grid, with the thickness at half the spacing: the contact distance is one grid step.
Scene small_heap(int n) {
  const double thickness = 0.5 / double(n - 1);
  return load_scene(shipped("heap256.json"),
                    {fmt::format("cloth.num_width_points={}", n), fmt::format("cloth.num_height_points={}", n),
                     fmt::format("cloth.thickness={:.17g}", thickness)});
}

// Two free masses of a 2 x 2 cloth placed by hand, at rest, then one resolve_self_contacts (the
// other row stays 10 m away).
struct Pair {
  Scene scene;
  ClothModel model;
  Constants<double> c;
  State<double> s;
  explicit Pair(double rest_gap)
      : scene(parse_scene(fmt::format(R"({{"cloth": {{"width": {:.17g}, "height": 10.0, "num_width_points": 2,
                  "num_height_points": 2, "thickness": 0.01, "orientation": 0}},
                  "simulation": {{"solver": "fabric", "self_collision": true}}}})",
                                          rest_gap),
                              "<pair>")),
        model(build_cloth(scene)), c(make_constants<double>(scene, model)), s(initial_state<double>(model)) {}
  double resolve_at(double gap) {
    s.pos[0] = Vec4<double>(0.3, 0.5, 0.5, s.pos[0].w);
    s.pos[1] = Vec4<double>(0.3 + gap, 0.5, 0.5, s.pos[1].w);
    s.disp.assign(4, Vec4<double>(0));
    build_spatial_hash(s.pos, c.inv_cell, s.hash);
    resolve_self_contacts(c, s);
    return s.pos[1].x - s.pos[0].x;
  }
};

// Steps `cpu` to frame 300 and returns the most intersecting triangle pairs at a tenth frame,
// with that frame in `at`.
size_t most_intersecting_to_300(CpuBackend<float>& cpu, const ClothModel& model, int* at = nullptr) {
  size_t worst = 0;
  for (int f = 1; f <= 300; ++f) {
    cpu.step_frame();
    if (f % 10) continue;
    const size_t n = count_self_intersections(model, cpu.snapshot());
    if (n > worst && at) *at = f;
    worst = std::max(worst, n);
  }
  return worst;
}

}  // namespace

TEST_CASE("bounded contact: two masses apart at rest are put exactly the contact distance apart", "[self_contact]") {
  Pair p(0.5);  // 0.5 m apart at rest: far more than the contact distance of 0.02 m
  REQUIRE(p.c.bounded_contact);
  CHECK(p.resolve_at(0.012) == Approx(0.02).epsilon(1e-12));
  // Each moved half the gap, and the push went into the displacement (x_prev kept).
  CHECK(p.s.disp[0].x == Approx(-0.004).epsilon(1e-9));
  CHECK(p.s.disp[1].x == Approx(0.004).epsilon(1e-9));
  CHECK(p.resolve_at(0.021) == Approx(0.021).margin(1e-15));  // out of contact: untouched
  CHECK(p.s.disp[0].x == 0.0);
}

TEST_CASE("bounded contact: neighbours closer at rest than the contact distance keep only their rest distance",
          "[self_contact]") {
  Pair p(0.015);  // neighbours 15 mm apart at rest, the contact distance 20 mm
  CHECK(p.resolve_at(0.005) == Approx(0.015).epsilon(1e-12));  // pushed back to rest, not to 20 mm
  CHECK(p.resolve_at(0.017) == Approx(0.017).margin(1e-15));  // further than at rest: not a contact
  CHECK(p.s.disp[0].x == 0.0);
}

TEST_CASE("the classic solver keeps the CS184 contact: no speed limit, no rest distances", "[self_contact]") {
  const Scene classic = load_scene(shipped("selfCollision.json"));
  const Constants<double> c = make_constants<double>(classic, build_cloth(classic));
  CHECK_FALSE(c.bounded_contact);
  CHECK(c.max_step == 0.0);
  CHECK(c.rest.empty());
}

TEST_CASE("bounded contact: predict moves no mass more than a quarter of the contact distance per substep",
          "[self_contact]") {
  // Free fall from 1 m onto nothing for 0.5 s: 4.9 m/s unlimited, 1.2 m/s here (0.25 * 2 *
  // thickness * 90 * 30 per second).
  const Scene scene = parse_scene(R"({"cloth": {"width": 1.0, "height": 1.0, "num_width_points": 7,
      "num_height_points": 5, "thickness": 0.0009, "orientation": 0},
      "simulation": {"solver": "fabric", "self_collision": true}})",
                                  "<fall>");
  const ClothModel model = build_cloth(scene);
  CpuBackend<double> cpu(scene, model);
  for (int f = 0; f < 45; ++f) cpu.step_frame();
  const ClothSnapshot snap = cpu.snapshot();
  const double limit = kMaxStepFraction * 2 * 0.0009;
  double largest = 0;
  for (auto& d : snap.disp) largest = std::max(largest, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
  INFO("largest displacement " << largest << " m per substep, limit " << limit);
  CHECK(largest <= limit * (1 + 1e-12));
  CHECK(largest >= limit * 0.999);  // it is falling at the limit
}

TEST_CASE("a 65 x 65 heap has no intersecting triangles at any tenth frame to 300", "[self_contact][slow]") {
  const Scene scene = small_heap(65);
  const ClothModel model = build_cloth(scene);
  CpuBackend<float> cpu(scene, model);
  int worst_frame = 0;
  const size_t worst = most_intersecting_to_300(cpu, model, &worst_frame);
  double top = -1e9;
  for (auto& p : cpu.snapshot().pos) top = std::max(top, p.y);
  INFO("most intersecting pairs " << worst << " (frame " << worst_frame << "); heap top " << top << " m");
  CHECK(worst == 0);
  CHECK(top < 0.2);  // it did collapse onto itself: layers lie on layers
}

TEST_CASE("the classic selfCollision scene has no intersecting triangles at any tenth frame to 300",
          "[self_contact][slow]") {
  const Scene scene = load_scene(shipped("selfCollision.json"));
  const ClothModel model = build_cloth(scene);
  CpuBackend<float> cpu(scene, model);
  CHECK(most_intersecting_to_300(cpu, model) == 0);
}

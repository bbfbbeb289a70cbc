// Placed particles and comparisons shared by the GPU self-collision tests (hash stages, response).
#pragma once

#include <glad/gl.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <random>
#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "analysis/intersections.hpp"
#include "prefix_scan.hpp"
#include "reference/reference.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace self_collision_fixtures {

using Positions = std::vector<Vec4<float>>;
using Cell = std::array<int32_t, 3>;

inline std::filesystem::path compute_dir() { return test::source_path("compute"); }

using test::mismatches;

inline float max_diff(const Positions& a, const Positions& b) {
  float m = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) m = std::max(m, std::abs(a[i][k] - b[i][k]));
  return m;
}

// The exact count of intersecting triangle pairs (host/core/analysis/intersections.hpp) of a downloaded state.
inline size_t intersections_of(const ClothModel& model, const State<float>& s) {
  std::vector<glm::dvec3> at;
  for (auto& p : s.pos) at.emplace_back(p.x, p.y, p.z);
  return count_self_intersections(model.triangles, at);
}

// One pass from an identical state: bit for bit on llvmpipe (docs/design.md §6), else within 1e-6 m.
inline void check_same_pass_result(const Positions& gpu, const Positions& cpu) {
  INFO("max |GPU - CPU| = " << max_diff(gpu, cpu) << " m");
  if (gl::gl_renderer_is_llvmpipe())
    CHECK(mismatches(gpu, cpu) == 0);
  else
    CHECK(max_diff(gpu, cpu) <= 1e-6f);
}

inline Cell cell_of(const Vec4<float>& p, const Constants<float>& c) {
  return {cell_coord(p.x, c.inv_cell), cell_coord(p.y, c.inv_cell), cell_coord(p.z, c.inv_cell)};
}
inline uint32_t bucket_of(const Cell& k, uint32_t table) { return hash_cell(k[0], k[1], k[2], table); }

// A scene whose particles a test places by hand; collide() runs self-collision on both sides.
struct Placed {
  Scene scene;
  ClothModel model = build_cloth(scene);
  Constants<float> c = make_constants<float>(scene, model);
  State<float> s = initial_state<float>(model);
  explicit Placed(Scene sc) : scene(std::move(sc)) {}
  // The GPU result; `s` is left after the CPU pass.
  Positions collide() {
    s.disp.assign(s.pos.size(), Vec4<float>(0));  // placed at rest
    GpuSimulator gpu(scene, model, compute_dir());
    gpu.upload(s);
    gpu.passes().collide_self();
    State<float> g;
    gpu.download(g);
    collide_self(c, s);
    return g.pos;
  }
  // A 33x17 grid folded in the middle: rows 9..16 lie back over rows 7..0, `gap` above them,
  // columns sx apart and rows sz apart, each coordinate jittered by up to 1 mm (seeded).
  void fold_33x17(float gap, float sx, float sz, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-1e-3f, 1e-3f);
    for (int y = 0; y < 17; ++y)
      for (int x = 0; x < 33; ++x) {
        const int row = y <= 8 ? y : 16 - y;
        Vec4<float>& p = s.pos[model.index(x, y)];
        p = Vec4<float>(float(x) * sx + jitter(rng), 1.f + (y <= 8 ? 0.f : gap) + jitter(rng),
                        float(row) * sz + jitter(rng), p.w);
      }
  }
  // The particles not placed by the test go far apart, out of everyone's reach.
  void park_from(int first) {
    for (int i = first; i < model.count(); ++i) s.pos[i] = Vec4<float>(5.f + 0.5f * float(i), 7.f, -3.f, s.pos[i].w);
  }
};

// Particle i moved from `before` to `after` by the average push of `others` (§1.3), in double.
inline void check_pushed(const Positions& after, const Positions& before, int i, std::vector<int> others,
                  const Constants<float>& c) {
  glm::dvec3 push(0);
  for (int j : others) {
    const glm::dvec3 e = glm::dvec3(before[i]) - glm::dvec3(before[j]);
    push += e * ((double(c.contact_distance) - glm::length(e)) / glm::length(e));
  }
  push /= double(others.size()) * double(c.steps);
  for (int k = 0; k < 3; ++k) CHECK(double(after[i][k]) - double(before[i][k]) == Approx(push[k]).margin(1e-7));
}

}  // namespace self_collision_fixtures
using namespace self_collision_fixtures;

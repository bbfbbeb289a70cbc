// What the material tests share (test_materials.cpp, test_material_bending.cpp): a strip of
// fabric with a material, a run of the CPU reference, a grid column's mean position.
#pragma once

#include <string>

#include <fmt/format.h>
#include <glm/vec3.hpp>

#include "backend.hpp"
#include "reference/reference.hpp"

namespace clothsim::test {

// A strip of fabric (fabric solver, a material of `stretch`, `shear`, `bending`, density
// 0.2 kg/m^2), nw x nh at spacing h, flat at y = 1 along x, with the given pins and gravity.
inline Scene strip(int nw, int nh, double h, const std::string& pins, glm::dvec3 gravity, const std::string& stretch,
                   double shear, double bending) {
  return parse_scene(
      fmt::format(R"({{"cloth": {{"width": {}, "height": {}, "num_width_points": {}, "num_height_points": {},
          "thickness": 0.001, "orientation": 0, "pinned": [{}], "damping": 0.5,
          "material": {{"density": 0.2, "stretch": {}, "shear": {}, "bending": {}}}}},
        "simulation": {{"solver": "fabric", "self_collision": false, "gravity": [{}, {}, {}]}}}})",
                  (nw - 1) * h, (nh - 1) * h, nw, nh, pins, stretch, shear, bending, gravity.x, gravity.y, gravity.z),
      "<strip>");
}

inline std::string pin_columns(int x0, int x1, int nh) {
  std::string s;
  for (int x = x0; x <= x1; ++x)
    for (int y = 0; y < nh; ++y) s += fmt::format("{}[{},{}]", s.empty() ? "" : ",", x, y);
  return s;
}

template <class R> State<R> run(const Scene& scene, int frames) {
  const ClothModel model = build_cloth(scene);
  CpuBackend<R> cpu(scene, model);
  for (int f = 0; f < frames; ++f) cpu.step_frame();
  return cpu.state();
}

// The mean position of grid column x.
template <class R> glm::dvec3 column(const State<R>& s, int nw, int nh, int x) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < nh; ++y) sum += glm::dvec3(s.pos[size_t(y * nw + x)]);
  return sum / double(nh);
}

}  // namespace clothsim::test

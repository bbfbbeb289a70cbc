// Panels for the sewing tests (tests/test_sewing.cpp, tests/test_gpu_sewing.cpp): flat OBJ
// panels in the xy plane and a scene of two of them, one hanging from the other by a seam.
#pragma once

#include <fstream>
#include <string>

#include <fmt/format.h>

#include "test_helpers.hpp"

namespace clothsim::test {

// An n x n panel of `size` metres in the plane z = `z`, its lower left corner at (x0, y0): vertex
// r * n + c at (x0 + c h, y0 + r h), rows from the bottom up (so the bottom row is 0 .. n - 1 and
// the top row n (n - 1) .. n n - 1), two triangles a cell.
inline std::string write_panel(const TempDir& dir, const std::string& name, int n, double size, double x0, double y0,
                               double z = 0) {
  const std::string path = dir / (name + ".obj");
  std::ofstream out(path);
  const double h = size / (n - 1);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) out << fmt::format("v {:.17g} {:.17g} {:.17g}\n", x0 + c * h, y0 + r * h, z);
  for (int r = 0; r + 1 < n; ++r)
    for (int c = 0; c + 1 < n; ++c) {
      const int a = r * n + c + 1, b = a + 1, d = a + n, e = d + 1;  // 1-based
      out << fmt::format("f {} {} {}\nf {} {} {}\n", a, b, e, a, e, d);
    }
  return path;
}

// Panel A (3 x 3, 0.2 m, ks_a) hangs from its top row over y in [0.2, 0.4]; panel B (ks_b)
// starts 5 cm below it, over [-0.05, 0.15], and its top row is sewn to A's bottom row. With
// `extra` appended to the simulation object.
inline std::string hanging_panels_scene(const TempDir& dir, const std::string& solver, double ks_a, double ks_b,
                                        bool self_collision, const std::string& extra = "") {
  const std::string a = write_panel(dir, "upper", 3, 0.2, 0, 0.2), b = write_panel(dir, "lower", 3, 0.2, 0, -0.05);
  return fmt::format(R"({{
  "cloth": [
    {{"mesh": "{}", "density": 0.15, "ks": {}, "damping": 1, "thickness": 0.004,
      "pinned_box": {{"min": [-1, 0.39, -1], "max": [1, 1, 1]}},
      "seams": [{{"vertices": [0, 1, 2], "to_cloth": 1, "to_vertices": [6, 7, 8]}}]}},
    {{"mesh": "{}", "density": 0.15, "ks": {}, "damping": 1, "thickness": 0.004}}
  ],
  "simulation": {{"solver": "{}", "self_collision": {}, "sewing_speed": 0.5{}}}
}})",
                     a, ks_a, b, ks_b, solver, self_collision ? "true" : "false", extra);
}

}  // namespace clothsim::test

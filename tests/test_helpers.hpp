// Small builders and comparisons shared by the tests of both tiers.
#pragma once

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "backend.hpp"
#include "analysis/diagnostics.hpp"
#include "scene/scene.hpp"

namespace clothsim::test {

// A scratch directory unique to this process, suite and test, removed at the end.
struct TempDir {
  std::filesystem::path path;
  TempDir(const std::string& suite, const std::string& name)
      : path(std::filesystem::temp_directory_path() / fmt::format("clothsim_test_{}_{}_{}", suite, getpid(), name)) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& f) const { return (path / f).string(); }
};

// A classic-style scene with the given grid and JSON fragments merged in by --set overrides.
inline Scene make_scene(int nw, int nh, int orientation, std::vector<std::string> sets = {},
                        const std::string& extra_top = "") {
  std::string text = fmt::format(
      R"({{"cloth": {{"width": 1.0, "height": 1.0, "num_width_points": {}, "num_height_points": {},
          "thickness": 0.0095, "orientation": {}}}{}}})",
      nw, nh, orientation, extra_top);
  return parse_scene(text, "<test>", sets);
}

// scripts/sphere-drape's drop: an n x n cloth of 1 m (fabric density, ks 5000, damping 0.2, no
// pins, no Provot limit, no self-collision) under fabric, 5 cm above a sphere of 0.2 m under its
// centre with `friction`.
inline Scene sphere_drape(int n, double friction) {
  return make_scene(n, n, 0,
                    {"cloth.pinned=[]", "cloth.density=0.15", "cloth.ks=5000", "cloth.damping=0.2",
                     "simulation.max_stretch=10", "simulation.self_collision=false", "simulation.solver=\"fabric\""},
                    fmt::format(R"(, "sphere": {{"origin": [0.5, 0.75, 0.5], "radius": 0.2, "friction": {}}})", friction));
}

// The --set override that pins every particle of grid row `row` of a cloth `width` points wide.
inline std::string pin_row(int width, int row) {
  std::string pins = "cloth.pinned=[";
  for (int x = 0; x < width; ++x) pins += fmt::format("{}[{},{}]", x ? "," : "", x, row);
  return pins + "]";
}

// Elements that differ bit for bit (so -0 vs 0 and NaN payloads count too); a size
// difference counts as the longer size.
template <class T> size_t mismatches(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
  return n;
}

// The SceneError a scene's text raises on the way to running it (parsed as `source`, its cloth
// built, a CPU backend made: the colliders' files loaded), or "(no error)".
inline std::string setup_error(const std::string& text, const std::string& source) {
  try {
    const Scene s = parse_scene(text, source);
    const ClothModel m = build_cloth(s);
    CpuBackend<double> cpu(s, m);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// The largest spring stretch at any of the first `frames` frames of the CPU reference (float).
inline double worst_stretch_over_frames(const Scene& s, int frames, uint64_t* settling_passes = nullptr) {
  const ClothModel m = build_cloth(s);
  CpuBackend<float> cpu(s, m);
  double worst = 0;
  for (int f = 1; f <= frames; ++f) {
    cpu.step_frame();
    worst = std::max(worst, measure(s, m, cpu.snapshot()).max_stretch_ratio);
  }
  if (settling_passes) *settling_passes = cpu.stretch_settling_passes();
  return worst;
}

inline double max_abs_diff(const std::vector<glm::dvec4>& a, const std::vector<glm::dvec4>& b) {
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(a[i][c] - b[i][c]));
  return m;
}

}  // namespace clothsim::test

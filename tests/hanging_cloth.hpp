// The hanging cloth of the stiffness tests (CPU and GPU tier): the resolution-independence
// cloth of issue 43, scenes/hang_xpbd.json at any size.
#pragma once

#include <fmt/format.h>

#include "scene/scene.hpp"
#include "test_helpers.hpp"

namespace clothsim::test {

// 1 m x 1 m, vertical, pinned at its two top corners, fabric density 0.15 kg/m^2, damping 0.2,
// max_stretch 10 (off), fabric (or `solver`) at 90 frames/s x 30 substeps, no self-collision.
inline Scene hanging_cloth(int n, double ks = 5000, const char* solver = "fabric") {
  return make_scene(n, n, 1,
                    {fmt::format("cloth.pinned=[[0,{0}],[{0},{0}]]", n - 1), "cloth.density=0.15",
                     fmt::format("cloth.ks={}", ks), "cloth.damping=0.2", "simulation.max_stretch=10",
                     "simulation.self_collision=false", fmt::format("simulation.solver=\"{}\"", solver)});
}

inline constexpr double kStiffnesses[] = {10, 1e3, 1e5, 1e7, 1e9};

}  // namespace clothsim::test

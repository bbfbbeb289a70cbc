// The cloth's static equilibrium (docs/model.md, "Static equilibrium"): where every free mass's
// spring forces balance its weight, found by Newton's method in double on the springs' potential
// energy, independently of either solver. A solver's rest state is checked against it
// (tests/test_closed_forms.cpp): a formula error both backends share shows up there.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "cloth/cloth.hpp"
#include "scene/scene.hpp"

namespace clothsim {

struct StaticEquilibrium {
  std::vector<glm::dvec3> pos;  // every particle; pinned ones where they start
  int iterations = 0;           // Newton steps taken
  double residual = 0;          // largest net force on a free mass at the end (N)
  bool converged = false;       // residual <= tolerance
};

// E(x) = sum over the enabled springs of ks'/2 (|xj - xi| - L)^2 - sum over the free masses of
// m g . x, with ks' the spring's stiffness (bending 0.2 ks) and m, g the scene's; pinned masses
// fixed. Levenberg-Marquardt-damped Newton (the springs' Hessians with the compressive part
// clamped, so each step solves a positive definite sparse system, Eigen's LDL^T) from the
// cloth's start positions, until the largest net force is at most `tolerance` newtons. No
// colliders, wind or self-collision: a scene with any of them is refused (std::invalid_argument).
// A cloth with every particle pinned is at rest where it starts: converged in 0 steps.
StaticEquilibrium solve_static_equilibrium(const Scene& scene, const ClothModel& model, double tolerance = 1e-10,
                                           int max_iterations = 200);

}  // namespace clothsim

// The Coulomb friction cases (docs/model.md, "Coulomb friction (fabric)") shared by the CPU tests
// and their GPU twin: a small cloth lying on a plane tilted by theta, at the surface offset.
#pragma once

#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "cloth/cloth.hpp"
#include "reference/reference.hpp"
#include "test_helpers.hpp"

namespace clothsim::test {

inline constexpr double kG = 9.8;  // m/s^2, the default gravity

struct Slope {
  Scene scene;
  ClothModel model;
  glm::dvec3 down;    // unit, down the slope
  glm::dvec3 normal;  // the plane's unit normal
};

// A 7x5 cloth of 0.3 m x 0.2 m (fabric density, the fabric solver, damping 0: damping acts per substep,
// so it would depend on the substep count), its rest centre on a plane through the origin whose
// normal is (-sin theta, cos theta, 0), with friction `mu`, at `steps` substeps of 90 frames/s.
// The grid is built flat and then turned about z into the plane, 1e-4 m (the surface offset)
// in front of it: it starts at rest, as a cloth that has settled there.
inline Slope slope(double theta_degrees, double mu, int steps) {
  const double theta = theta_degrees * M_PI / 180.0;
  Slope s{make_scene(7, 5, 0,
                     {"cloth.width=0.3", "cloth.height=0.2", "cloth.density=0.15", "cloth.damping=0",
                      "simulation.solver=\"fabric\"", "simulation.self_collision=false",
                      fmt::format("simulation.simulation_steps={}", steps)},
                     fmt::format(R"(, "plane": {{"point": [0, 0, 0], "normal": [{:.17g}, {:.17g}, 0], "friction": {}}})",
                                 -std::sin(theta), std::cos(theta), mu)),
          {}, {}, {}};
  s.model = build_cloth(s.scene);
  s.normal = s.scene.planes[0].normal;
  const glm::dvec3 along(s.normal.y, -s.normal.x, 0.0);  // in the plane, across z; up the slope
  s.down = -along;
  const glm::dvec3 centre(0.15, 1.0, 0.1);
  for (glm::dvec3& p : s.model.initial) {
    const glm::dvec3 r = p - centre;  // r.y = 0: the grid is horizontal
    p = along * r.x + glm::dvec3(0, 0, r.z) + s.normal * 1e-4;
  }
  return s;
}

// g (sin theta - mu cos theta): the closed-form acceleration down the slope (0 when it holds).
inline double sliding_acceleration(double theta_degrees, double mu) {
  const double theta = theta_degrees * M_PI / 180.0;
  return std::max(0.0, kG * (std::sin(theta) - mu * std::cos(theta)));
}

// The mean displacement down the slope since the start, and the furthest any mass is from it.
struct SlopeMotion {
  double mean_down = 0;
  double max_distance = 0;
  double min_clearance = INFINITY, max_clearance = -INFINITY;  // from the plane, m
};
template <class V> SlopeMotion slope_motion(const Slope& s, const std::vector<V>& pos) {
  SlopeMotion m;
  for (size_t i = 0; i < pos.size(); ++i) {
    const glm::dvec3 x(pos[i].x, pos[i].y, pos[i].z), moved = x - s.model.initial[i];
    m.mean_down += glm::dot(moved, s.down) / double(pos.size());
    m.max_distance = std::max(m.max_distance, glm::length(moved));
    const double clearance = glm::dot(x, s.normal);
    m.min_clearance = std::min(m.min_clearance, clearance);
    m.max_clearance = std::max(m.max_clearance, clearance);
  }
  return m;
}

}  // namespace clothsim::test

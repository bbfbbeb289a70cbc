// Physics against closed forms (issue 22 item 3), shared by the CPU tests and their GPU twins
// (test_closed_forms.cpp, test_gpu_closed_forms.cpp): a hanging chain's link stretches, a
// stretched chain's lowest frequency, and a loaded sheet against the static solve. Each scene
// runs under either solver; the answers come from formulas or from solve_static_equilibrium,
// never from a run.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cloth/cloth.hpp"
#include "test_helpers.hpp"

namespace clothsim::test {

// The chains: a 2 x 11 grid, 0.1 m x 1 m, lying in the y = 1 plane along z, with only its
// structural springs (two chains of 11 masses along z, joined by rungs that hang straight and
// carry nothing), its top row (z = 1) pinned. ks 50 N/m, density 0.15 kg/m^2 (each mass
// 0.1 x 1 x 0.15 / 22 kg), max_stretch 10 (no Provot limit helping), 90 frames/s x 30 substeps.
inline constexpr int kChainMasses = 11;  // per chain, the pinned one included
inline constexpr double kChainKs = 50;
inline constexpr double kChainMass = 0.1 * 1.0 * 0.15 / (2 * kChainMasses);
inline constexpr double kChainLink = 1.0 / (kChainMasses - 1);

inline Scene chain_scene(const std::string& solver, std::vector<std::string> sets) {
  sets.insert(sets.begin(), {"cloth.width=0.1", "cloth.height=1.0", "cloth.density=0.15",
                             fmt::format("cloth.ks={}", kChainKs), "cloth.enable_shearing=false",
                             "cloth.enable_bending=false",
                             fmt::format("cloth.pinned=[[0,{0}],[1,{0}]]", kChainMasses - 1),
                             "simulation.max_stretch=10",
                             "simulation.self_collision=false", "simulation.solver=\"" + solver + "\""});
  return make_scene(2, kChainMasses, 0, sets);
}

// Hanging under gravity (9.8 m/s^2 along -z), damped to rest: damping 1 (keep 0.99 per substep).
inline Scene hanging_chain(const std::string& solver) {
  return chain_scene(solver, {"cloth.damping=1", "simulation.gravity=[0.0, 0.0, -9.8]"});
}

// Link k (k = 1 at the pin) of a chain at rest carries the weight of the masses below it:
// its stretch is (kChainMasses - k) m g / ks.
inline double chain_link_stretch(int k) { return (kChainMasses - k) * kChainMass * 9.8 / kChainKs; }

// The z of mass y (y = 0 at the free end) of chain x in `pos`, the grid's row-major order.
template <class V> double chain_z(const std::vector<V>& pos, int x, int y) { return double(pos[size_t(2 * y + x)].z); }

// The largest relative error of a link's stretch against chain_link_stretch, over both chains.
template <class V> double chain_stretch_error(const std::vector<V>& pos) {
  double worst = 0;
  for (int x = 0; x < 2; ++x)
    for (int k = 1; k < kChainMasses; ++k) {
      const int upper = kChainMasses - k, lower = upper - 1;
      const double stretch = chain_z(pos, x, upper) - chain_z(pos, x, lower) - kChainLink;
      worst = std::max(worst, std::abs(stretch / chain_link_stretch(k) - 1));
    }
  return worst;
}

// Free oscillation: no gravity, no damping, started at rest in the chain's lowest mode.
inline Scene free_chain(const std::string& solver) {
  return chain_scene(solver, {"cloth.damping=0", "simulation.gravity=[0.0, 0.0, 0.0]"});
}

// A chain of N free masses fixed at one end: mode 1 has u_j = sin(j theta), theta = pi / (2N + 1),
// j = 1 .. N counted from the pin, at omega = 2 sqrt(ks / m) sin(theta / 2).
inline double chain_mode_theta() { return M_PI / (2 * (kChainMasses - 1) + 1); }
inline double chain_mode_omega() { return 2 * std::sqrt(kChainKs / kChainMass) * std::sin(chain_mode_theta() / 2); }
// The start: every free mass moved away from the pin by `amplitude` sin(j theta) (all links
// stretched, the end by `amplitude`... times sin(N theta)), at rest (d = 0).
template <class V> void stretch_into_mode(std::vector<V>& pos, double amplitude) {
  for (int x = 0; x < 2; ++x)
    for (int j = 1; j < kChainMasses; ++j) {
      auto& p = pos[size_t(2 * (kChainMasses - 1 - j) + x)];
      p.z = decltype(p.z)(double(p.z) - amplitude * std::sin(j * chain_mode_theta()));
    }
}

// The angular frequency of a signal sampled every `dt`, from its upward zero crossings
// (interpolated linearly between samples); 0 if it crosses fewer than 5 times.
inline double measured_omega(const std::vector<double>& u, double dt, int* periods) {
  std::vector<double> t;
  for (size_t k = 1; k < u.size(); ++k)
    if (u[k - 1] < 0 && u[k] >= 0) t.push_back((double(k - 1) + u[k - 1] / (u[k - 1] - u[k])) * dt);
  *periods = int(t.size()) - 1;
  if (t.size() < 5) return 0;
  return 2 * M_PI / ((t.back() - t.front()) / double(t.size() - 1));
}
inline constexpr double kModeAmplitude = 0.02;  // m, stretch_into_mode's
inline constexpr int kModeFrames = 150;         // about 10 periods at 90 frames/s

// The loaded sheet: a horizontal 33 x 33 cloth, 1 m x 1 m at y = 1, every border mass pinned,
// under gravity, ks 100 N/m and density 0.15 kg/m^2 with every spring type, max_stretch 10,
// damping 1 (so it comes to rest), 90 frames/s x 30 substeps.
inline Scene loaded_sheet(const std::string& solver) {
  const int n = 33;
  std::string pins;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if (x == 0 || y == 0 || x == n - 1 || y == n - 1) pins += fmt::format("{}[{},{}]", pins.empty() ? "" : ",", x, y);
  return make_scene(n, n, 0,
                    {"cloth.pinned=[" + pins + "]", "cloth.density=0.15", "cloth.ks=100", "cloth.damping=1",
                     "simulation.max_stretch=10",
                     "simulation.self_collision=false", "simulation.solver=\"" + solver + "\""});
}

// The largest distance of a particle of `pos` from the static solve's.
template <class V> double distance_from(const std::vector<V>& pos, const std::vector<glm::dvec3>& eq) {
  double worst = 0;
  for (size_t i = 0; i < pos.size(); ++i) worst = std::max(worst, glm::length(glm::dvec3(pos[i]) - eq[i]));
  return worst;
}
inline constexpr int kRestFrames = 300;  // frames to rest for the chain and the sheet (damping 1)

}  // namespace clothsim::test

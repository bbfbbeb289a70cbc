#include "analysis/divergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include <fmt/format.h>
#include <glm/common.hpp>

#include "scene/scene_table.hpp"
#include "../../../compute/shared/divergence.glsl"

namespace clothsim {
namespace {

// A substep is comfortably stable below half of sqrt(m / ks): measured on 7x5 and 50x50 cloths,
// runs blow up from about 3 x sqrt(m / ks) and stay calm below 0.5 x.
constexpr double kStableStepFraction = 0.5;

double farthest_reach(const ClothBounds& b, const DivergenceLimits& l) {
  double reach = 0;
  for (int k = 0; k < 3; ++k)
    reach = std::max({reach, double(b.hi[k]) - double(l.centre[k]), double(l.centre[k]) - double(b.lo[k])});
  return reach;
}

// The largest simulation_steps the loader accepts, from its row: advice never suggests more.
int max_simulation_steps() {
  for (const Param<SimulationParams>& p : param_rows<SimulationParams>())
    if (std::string_view(p.info.key) == "simulation_steps") return int(p.info.hi);
  return 1;
}

}  // namespace

DivergenceLimits divergence_limits(const Scene&, const ClothModel& model) {
  // The cloth's own extent, not the grid's width and height (a mesh cloth has none of its own):
  // a mesh in millimetres or with one stray vertex far out starts within its limit.
  glm::dvec3 centre(0), lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const glm::dvec3& p : model.initial) centre += p, lo = glm::min(lo, p), hi = glm::max(hi, p);
  centre /= double(model.count());
  // The start's own reach from its centre is at most its largest side, far within the limit.
  const glm::dvec3 size = hi - lo;
  return {glm::vec3(centre), float(1000.0 * std::max({size.x, size.y, size.z}))};
}

bool within_limits(const ClothBounds& b, const DivergenceLimits& l) {
  return b.finite && shared::bounds_within(b.lo, b.hi, l.centre, l.limit);
}

std::optional<std::string> divergence_message(const Scene& scene, const ClothModel& model, const FrameCheck& check) {
  const DivergenceLimits limits = divergence_limits(scene, model);
  if (within_limits(check.bounds, limits)) return std::nullopt;
  const std::string what =
      check.bounds.finite
          ? fmt::format("the cloth reached {:.3g} m from where it started (limit {:.3g} m)",
                        farthest_reach(check.bounds, limits), limits.limit)
          : std::string("a particle position became NaN/Inf");
  // The particle with the least mass per stiffness sets the stable step: the model's own masses
  // (a mesh cloth's differ per vertex) and its cloth's ks.
  const auto cloths = scene.cloths();
  const std::vector<double> masses = particle_masses(scene, model);  // follows a live density edit
  double ks = 0, mass = 0, ratio = HUGE_VAL;
  for (size_t i = 0; i < size_t(model.count()); ++i) {
    const double k = cloths[model.material[i]]->spring_ks(), m = masses[i];
    if (model.pinned[i] || !(k > 0) || !(m / k < ratio)) continue;
    ratio = m / k, ks = k, mass = m;
  }
  // A material's stiffness is its stretch (ks here stands for it: ClothParams::spring_ks).
  const char* ks_key = scene.cloth.material ? "cloth.material.stretch (as a spring constant)" : "cloth.ks";
  const double dt = scene.dt();
  const int steps = scene.simulation.simulation_steps;
  const int max_steps = max_simulation_steps();
  const double stable_dt = ratio < HUGE_VAL ? kStableStepFraction * std::sqrt(ratio) : HUGE_VAL;
  std::string cause;
  if (dt > stable_dt) {
    // Enough substeps for stable_dt, rounded up to a multiple of 10 and at least twice as many,
    // and never more than the loader accepts; past that, only a softer cloth is stable.
    const double needed = std::ceil(1.0 / (scene.simulation.frames_per_sec * stable_dt) / 10.0) * 10.0;
    const long long suggest = std::min<long long>(std::max(2LL * steps, (long long)std::min(needed, 1e9)), max_steps);
    // The ks at which the present substeps are stable.
    const double soft_ks = mass * std::pow(kStableStepFraction / dt, 2);
    cause = fmt::format(
        "Likely cause: the springs are too stiff for the time step (ks {:g} N/m on {:.3g} kg particles needs "
        "substeps shorter than about {:.2g} s; these are {:.2g} s). Lower {} (now {:g}; about {:.3g} is stable "
        "with these substeps)",
        ks, mass, stable_dt, dt, ks_key, ks, soft_ks);
    if (steps < max_steps)
      cause += fmt::format(" or raise simulation.simulation_steps (now {}, at most {}), e.g. --set "
                           "simulation.simulation_steps={}",
                           steps, max_steps, suggest);
  } else if (steps < max_steps) {
    cause = fmt::format(
        "Likely cause: extreme parameters (cloth.ks {:g}, cloth.density {:g}, simulation.gravity, colliders); "
        "more substeps usually help: raise simulation.simulation_steps (now {}), e.g. --set "
        "simulation.simulation_steps={}",
        scene.cloth.ks, scene.cloth.density, steps, std::min(4LL * steps, (long long)max_steps));
  } else {
    cause = fmt::format(
        "Likely cause: extreme parameters (cloth.ks {:g}, cloth.density {:g}, simulation.gravity, colliders); "
        "simulation.simulation_steps is already at its largest ({}): soften the cloth or the colliders' motion",
        scene.cloth.ks, scene.cloth.density, steps);
  }
  return fmt::format("the simulation diverged at frame {}: {}. {}", check.frame, what, cause);
}

template <class R> ClothBounds check_divergence(const std::vector<Vec4<R>>& pos) {
  ClothBounds b;
  b.lo = glm::vec3(std::numeric_limits<float>::infinity());
  b.hi = glm::vec3(-std::numeric_limits<float>::infinity());
  for (const Vec4<R>& p : pos) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      b.finite = false;
      continue;
    }
    // Rounded to float before the comparison: min/max commute with rounding, so this is the
    // box of the float positions, as the GPU reduces it. A double beyond float's range is
    // clamped to it, so it still counts as far away rather than as Inf.
    const double big = std::numeric_limits<float>::max();
    const glm::vec3 x(glm::clamp(glm::dvec3(p.x, p.y, p.z), -big, big));
    b.lo = glm::min(b.lo, x);
    b.hi = glm::max(b.hi, x);
  }
  return b;
}

template <class R>
void keep_last_good(const ClothBounds& bounds, const DivergenceLimits& limits, int frame,
                    const std::vector<Vec4<R>>& pos, KeptFrame<R>& kept) {
  if (kept.tripped) return;
  if (!within_limits(bounds, limits)) {
    kept.tripped = true;
    return;
  }
  kept.pos = pos;
  kept.frame = frame;
}

template <class R> ClothSnapshot snapshot_of_positions(const ClothModel& model, const std::vector<Vec4<R>>& pos) {
  State<R> s;
  s.pos = pos;
  s.normal.resize(pos.size());
  compute_normals(model, s);
  ClothSnapshot out;
  for (auto& p : s.pos) out.pos.emplace_back(p);
  out.disp.assign(out.pos.size(), glm::dvec4(0));  // shown at rest
  for (auto& n : s.normal) out.normal.emplace_back(n);
  return out;
}

#define CLOTHSIM_INSTANTIATE(R)                                                                              \
  template ClothBounds check_divergence<R>(const std::vector<Vec4<R>>&);                                    \
  template void keep_last_good<R>(const ClothBounds&, const DivergenceLimits&, int, const std::vector<Vec4<R>>&, \
                                  KeptFrame<R>&);                                                          \
  template ClothSnapshot snapshot_of_positions<R>(const ClothModel&, const std::vector<Vec4<R>>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

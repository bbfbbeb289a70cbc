// The divergence guard, the same on both backends: after every frame, check_divergence
// reduces the positions to a bounding box and a NaN/Inf flag; a frame passes when it is finite
// and its box stays within a limit around where the cloth started; keep_last_good keeps the
// newest frame that passed, so a diverged run can still export a finite cloth. The GPU twins
// are compute/check_divergence.comp and compute/keep_last_good.comp, and one function,
// divergence_message, tells the user what happened whichever backend found it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "analysis/diagnostics.hpp"
#include "reference/reference.hpp"

namespace clothsim {

// One frame as check_divergence sees it. Float, exactly what the GPU reduction produces.
struct ClothBounds {
  bool finite = true;  // no position coordinate is NaN or Inf
  glm::vec3 lo{0}, hi{0};  // bounding box of the finite positions (lo > hi if there are none)
};

struct FrameCheck {
  int frame = 0;  // 1 = the first simulated frame
  ClothBounds bounds;
};

// Where the cloth started (the mean of its initial positions) and how far from there, per
// axis, it may reach: 1000 x its larger side. Float, as the GPU compares.
struct DivergenceLimits {
  glm::vec3 centre{0};
  float limit = 0;
};
DivergenceLimits divergence_limits(const Scene& scene, const ClothModel& model);

// Whether a frame passes: finite, and hi - centre and centre - lo at most `limit` on every
// axis. Float arithmetic in the order of within_limits() in compute/divergence.glsl, so the
// host and the GPU's keep_last_good always agree.
bool within_limits(const ClothBounds& bounds, const DivergenceLimits& limits);

// The user-facing explanation of a failed check (which frame, what went wrong, the likely
// cause and what to change), or nullopt when the frame passes.
std::optional<std::string> divergence_message(const Scene& scene, const ClothModel& model, const FrameCheck& check);

// CPU twin of check_divergence.comp.
template <class R> ClothBounds check_divergence(const std::vector<Vec4<R>>& pos);

// What keep_last_good maintains: the newest frame that passed, as long as none has failed.
template <class R> struct KeptFrame {
  std::vector<Vec4<R>> pos;  // w = inverse mass, as in State
  int frame = 0;             // 0 = the initial state
  bool tripped = false;      // a frame failed: no later frame is kept, even one that passes
};

// CPU twin of keep_last_good.comp: keeps `pos` as frame `frame` if it passed and none failed before.
template <class R>
void keep_last_good(const ClothBounds& bounds, const DivergenceLimits& limits, int frame,
                    const std::vector<Vec4<R>>& pos, KeptFrame<R>& kept);

// A snapshot from positions alone (a kept frame): prev = pos, normals computed as the last
// pass of a frame computes them.
template <class R> ClothSnapshot snapshot_of_positions(const ClothModel& model, const std::vector<Vec4<R>>& pos);

}  // namespace clothsim

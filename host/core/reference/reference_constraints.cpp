// The reference's constraint passes: Provot's length limit (classic, docs/design.md §1 step 5;
// fabric's enforce_stretch_limit), colour by colour in the GPU's order.
#include <algorithm>

#include "reference/reference.hpp"
#include "reference/reference_detail.hpp"
#include "reference/reference_skinning.hpp"
#include "../../../compute/shared/springs.glsl"

namespace clothsim {

namespace {

// Calls visit(spring) for every spring of `colour` whose type is enabled in its cloth, in list
// order: the springs of a colour share no particle, so the order does not change the result
// (the GPU dispatches them at once, constraint_colour.glsl).
template <class R, class Visit>
void for_each_spring_of_colour(const ClothModel& m, const Constants<R>& c, int colour, Visit&& visit) {
  for (uint32_t k = m.colour_start[colour]; k < m.colour_start[colour + 1]; ++k)
    if (c.enabled(m.springs[k])) visit(m.springs[k]);
}

using shared::limit_stretch;  // Provot's projection (compute/shared/springs.glsl)

// One colour of the length constraint; with `over`, a watched pass's (enforce_stretch_limit):
// set when a spring is longer than kStretchSettled times its limit as its colour is solved.
template <class R>
void limit_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s, bool* over) {
  for_each_spring_of_colour(m, c, colour, [&](const Spring& sp) {
    const uint32_t i = sp.i, j = sp.j;
    const R wi = s.pos[i].w, wj = s.pos[j].w, wsum = wi + wj;
    if (wsum == R(0)) return;
    Vec3<R> xi(s.pos[i]), xj(s.pos[j]), di(s.disp[i]), dj(s.disp[j]);
    const R limit = c.stretch_limit * c.rest_of(sp);
    if (over && length3(xj - xi) > limit * R(kStretchSettled)) *over = true;
    if (!limit_stretch(xi, xj, di, dj, wi, wj, wsum, limit)) return;
    // Provot's pull may not leave a mass deeper than 0.1 mm inside a collider or behind a
    // plane (docs/model.md, "Colliders: contact that holds"); shallower, nothing changes.
    if (c.has_colliders()) {
      if (wi != R(0)) keep_out_of_colliders(c, xi, di, skin_slots(c, s, i));
      if (wj != R(0)) keep_out_of_colliders(c, xj, dj, skin_slots(c, s, j));
    }
    s.pos[i] = Vec4<R>(xi, wi);
    s.pos[j] = Vec4<R>(xj, wj);
    s.disp[i] = Vec4<R>(di, R(0));
    s.disp[j] = Vec4<R>(dj, R(0));
  });
}
}  // namespace

template <class R>
void solve_length_constraint_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s) {
  limit_colour(m, c, colour, s, nullptr);
}

// `passes` sweeps of the length constraint over every colour: the classic solver's
// (constraint_iterations) and fabric's enforce_stretch_limit (stretch_passes), as
// GpuSimulator::length_constraint_passes.
namespace {
template <class R>
void length_constraint_passes(const ClothModel& m, const Constants<R>& c, int passes, State<R>& s, bool* over = nullptr) {
  for (int pass = 0; pass < passes; ++pass)
    for (int colour = 0; colour < m.colours(); ++colour) limit_colour(m, c, colour, s, over);
}
}  // namespace

template <class R> void solve_length_constraints(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  length_constraint_passes(m, c, c.iterations, s);
}

template <class R> void enforce_stretch_limit(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  if (c.stretch_passes_max <= c.stretch_passes) {
    length_constraint_passes(m, c, c.stretch_passes, s);
    return;
  }
  // The fixed passes but the last, then the watched ones: the last fixed pass (one, with none
  // fixed) always runs, each settling pass only while the pass before it found a spring over.
  const int fixed = std::max(c.stretch_passes, 1);
  length_constraint_passes(m, c, fixed - 1, s);
  bool over = true;
  for (int pass = fixed - 1; pass < c.stretch_passes_max && arm_stretch_pass(over); ++pass) {
    if (pass >= fixed) ++s.stretch_settling_passes;
    length_constraint_passes(m, c, 1, s, &over);
  }
}

#define CLOTHSIM_INSTANTIATE(R) \
  template void solve_length_constraint_colour<R>(const ClothModel&, const Constants<R>&, int, State<R>&); \
  template void solve_length_constraints<R>(const ClothModel&, const Constants<R>&, State<R>&); \
  template void enforce_stretch_limit<R>(const ClothModel&, const Constants<R>&, State<R>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

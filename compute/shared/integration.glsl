// A mass's move over one substep (docs/design.md §1 step 2, docs/model.md): Verlet's, xpbd's
// prediction with its speed limit and tether, and a moving pin's. Included by
// compute/pinned_motion.glsl, advance.comp, integrate.comp, predict.comp and by
// host/core/reference/reference_forces.cpp; reading and writing the particles stay with each
// backend.
#ifndef CLOTHSIM_SHARED_INTEGRATION_GLSL
#define CLOTHSIM_SHARED_INTEGRATION_GLSL

#include "vector.glsl"

SHARED_BEGIN

// The bounded contact's speed limit (docs/model.md, "Self-contact that holds"): d shortened to
// max_step where it is longer.
SHARED_FN VEC3 limit_step(VEC3 d, REAL max_step) {
  REAL len = length3(d);
  PRECISE REAL scale = max_step * (REAL(1) / len);
  PRECISE VEC3 limited = d * scale;
  return len > max_step ? limited : d;
}

// The speed clamp's last word (limit_speed.comp and the reference's limit_speed): a mass at x
// that a substep moved by d, taken back along d to max_move from where it started.
SHARED_FN void limit_speed_of(INOUT(VEC3) x, INOUT(VEC3) d, REAL max_move) {
  PRECISE VEC3 limited = limit_step(d, max_move);
  PRECISE VEC3 start = x - d;
  PRECISE VEC3 end = start + limited;
  x = end;
  d = limited;
}

// The speed clamp (simulation.max_speed): a substep's move d no longer than max_move =
// max_speed * dt (0: no limit), as limit_step shortens it.
SHARED_FN VEC3 speed_clamped(VEC3 d, PARAMS params) {
  return params.max_move > REAL(0) ? limit_step(d, params.max_move) : d;
}

// d' = (1 - damping) d + a dt^2 with a = f w (keep = 1 - damping, w the inverse mass), the
// substep's displacement (d = x - x_prev kept as its own vector); then x' = x + d'.
// (advance.comp, integrate.comp and the reference's integrate; params: the step's block.)
SHARED_FN VEC3 verlet_move(VEC3 d, REAL keep, VEC3 f, REAL w, PARAMS params) {
  PRECISE VEC3 a = f * w;
  PRECISE VEC3 next_d = d * keep + a * params.dt2;
  return speed_clamped(next_d, params);
}

// Where the multigrid solve starts, as its offset x - y from the prediction y (predict.comp and
// the reference's predict; docs/solvers.md, "The fabric solver"). Without adaptive_rho (a
// test's, or no external move): back by the whole external move u = acc dt^2, which the solve
// then applies with the springs, so a cloth at rest starts where it rests. fabric: back by the share of u that the mass did not
// take in the substep before, read from that substep's offset `last` (x - y at its end, so
// last + u is its move beyond inertia): a falling or buckling mass starts at y, with all of it,
// a resting one where it rests, with none (the adaptive start of Chen et al. 2024, VBD).
// Where the mass is stiff for its inertia, rho = ks dt^2 / m above params.adaptive_rho, that
// share is scaled by adaptive_share: one V-cycle and one sweep do not take back a whole
// substep's fall there, and a start that hands them one tears the cloth at the pins (the 513²
// hang at rho 1,200: docs/solvers.md). `stiffness_per_mass` is ks / m (ks w).
// a * (1 / b), not a / b here: GLSL may compute a quotient as that product, the reference must too.
SHARED_FN REAL adaptive_share(REAL stiffness_per_mass, PARAMS params) {
  PRECISE REAL rho = stiffness_per_mass * params.dt2;
  PRECISE REAL ratio = params.adaptive_rho * (REAL(1) / rho);
  PRECISE REAL scaled = ratio * ratio;
  return rho > params.adaptive_rho ? scaled : REAL(1);
}

SHARED_FN VEC3 solve_start_offset(VEC3 acc, VEC3 last, REAL stiffness_per_mass, PARAMS params) {
  PRECISE VEC3 u = acc * params.dt2;
  REAL uu = dot3(u, u);
  if (!(params.adaptive_rho > REAL(0)) || !(uu > REAL(0))) return -u;
  PRECISE VEC3 taken_move = last + u;
  REAL taken = min(max(dot3(taken_move, u) * (REAL(1) / uu), REAL(0)), REAL(1));
  PRECISE REAL share = taken * adaptive_share(stiffness_per_mass, params);
  PRECISE VEC3 back = u * (REAL(1) - share);
  return -back;
}

// The fold threshold at a coarse vertex whose particle has `stiffness_per_mass` (ks w):
// params.folded_chord where fabric's start keeps its whole share, moving towards multigrid's
// 99 % (params.folded_chord_stiff) as the share drops (adaptive_share). A slack chord's vertex
// left free in the coarse problem steers its correction by a chord that says nothing of the
// buckled cloth; where the coarse problem carries most of the stiffness (high rho) that
// correction tears the cloth (the 513² hang at 95 %), where it carries little the free vertex
// lets a swing swing (docs/solvers.md).
SHARED_FN REAL folded_chord_at(REAL stiffness_per_mass, PARAMS params) {
  REAL share = params.adaptive_rho > REAL(0) ? adaptive_share(stiffness_per_mass, params) : REAL(1);
  PRECISE REAL chord = params.folded_chord + (params.folded_chord_stiff - params.folded_chord) * (REAL(1) - share * share);
  return chord;
}

// predict's move: damped Verlet under the external forces alone (the springs act in the solve).
SHARED_FN VEC3 predicted_move(VEC3 d, REAL keep, VEC3 acc, PARAMS params) {
  PRECISE VEC3 next_d = d * keep + acc * params.dt2;
  return speed_clamped(next_d, params);
}

// Where a pin that follows pinned_motion is at the end of the substep: its anchor plus the
// motion's offset then.
SHARED_FN VEC3 pin_target(VEC3 anchor, VEC3 offset) {
  PRECISE VEC3 x = anchor + offset;
  return x;
}

SHARED_END

#endif

// Pinned masses that follow cloth.pinned_motion: at the end of every substep a pinned mass is
// at its start position plus the offset of the substep's end, and its displacement is that
// move (the formulas are compute/shared/integration.glsl's). Held particles (the viewer's grab,
// also w = 0) have anchor w 0 and stay where they are held.
#ifndef CLOTHSIM_PINNED_MOTION_GLSL
#define CLOTHSIM_PINNED_MOTION_GLSL

#include "features.glsl"
#include "shared/integration.glsl"

layout(std430, binding = BINDING_ANCHORS) readonly buffer Anchors { vec4 anchor[]; };

// Where pinned mass k is at the end of this substep, if it follows pinned_motion.
bool moving_pin_position(int k, out vec3 x) {
  x = vec3(0.0);
  if (!PINS_MOVE) return false;
  vec4 a = anchor[k];
  if (a.w == 0.0) return false;
  x = pin_target(a.xyz, control.pin_offset);
  return true;
}

// p: the pinned particle's position (w 0); returns false if it does not move.
bool move_pinned(int i, vec4 p, out vec4 next, out vec3 d) {
  next = p;
  d = vec3(0.0);
  vec3 x;
  if (!moving_pin_position(i, x)) return false;
  precise vec3 moved = x - p.xyz;
  next = vec4(x, p.w);
  d = moved;
  return true;
}

#endif

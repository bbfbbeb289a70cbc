// Reads forces, positions and displacements; writes positions and displacements in place.
// One invocation per particle (damped Verlet; pinned particles, w = 0, stay put).
// The step runs advance, which fuses this with the forces; this pass stays for the pass checks.
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"
#include "pinned_motion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) buffer Displacements { vec4 disp[]; };
layout(std430, binding = BINDING_FORCES) readonly buffer Forces { vec4 force[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  vec4 p = pos[i];
  if (p.w == 0.0) {
    vec4 next;
    vec3 moved;
    if (move_pinned(int(i), p, next, moved)) {
      disp[i] = vec4(moved, 0.0);
      pos[i] = next;
    }
    return;
  }
  // d' = (1 - damping) d + a dt^2, x' = x + d' (docs/design.md §1 step 2 with d = x - x_prev).
  precise vec3 d = verlet_move(disp[i].xyz, material_of(int(i)).keep.x, force[i].xyz, p.w, params);
  precise vec3 next = p.xyz + d;
  disp[i] = vec4(d, 0.0);
  pos[i] = vec4(next, p.w);
}

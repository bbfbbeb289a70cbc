// Reads positions and displacements (through the views), the springs' multipliers, the wind
// forces, the tethers and the colliders; writes positions and displacements in place. One invocation per particle: the
// xpbd solver's first pass (docs/model.md), damped Verlet under gravity (and the wind) alone,
// the springs being constraints solved after it, then the particle's tether to its nearest pin;
// with u_collide_objects the collision objects follow in the same invocation. The CPU twin is
// predict() in host/core/reference/reference.cpp. Pinned particles (w = 0) stay, or follow pinned_motion.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "contact_list.glsl"
#include "pinned_motion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
layout(std430, binding = BINDING_WIND_FORCES) readonly buffer WindForces { vec4 wind_force[]; };
// multigrid only; fabric reads the last substep's offset first (solve_start_offset)
layout(std430, binding = BINDING_MG_OFFSET) buffer Offsets { vec4 offset[]; };

uniform bool u_collide_objects;

// Where pin k is at the end of this substep. A moving pin is read from its anchor, not from
// the positions this pass is writing, so the tethers race with nothing.
vec3 pin_position(int k) {
  vec3 x;
  return moving_pin_position(k, x) ? x : position_of(k).xyz;
}

// Particle i's prediction; true where a collider may move it (listed for collide_objects).
bool predict_particle(int i) {
  vec4 p = position_of(i);
  if (p.w == 0.0) {
    if (MULTIGRID_SOLVER) offset[i] = vec4(0.0);
    vec4 next;
    vec3 moved;
    if (move_pinned(i, p, next, moved)) {
      pos[i] = next;
      disp[i] = vec4(moved, 0.0);
    }
    return false;
  }
  precise vec3 acc = params.gravity;
  if (WIND_ENABLED) acc = acc + wind_force[i].xyz * p.w;  // compute_wind_forces ran before
  // The springs' multipliers of the last substep, as their forces over this one (times dt^2):
  // -n lambda on a spring's i end, +n lambda on its j end, in the gather order.
  // (The multigrid solver carries none: its springs act in its own solve.)
  // (A compile-time if: a loop of zero trips would still run its body once on llvmpipe.)
  precise vec3 warm = vec3(0.0);
  if (!MULTIGRID_SOLVER) {
    uint first = texelFetch(gather_start_view, i).x, last = texelFetch(gather_start_view, i + 1).x;
    for (uint g = first; g < last; ++g) {
      uvec4 entry = texelFetch(gather_view, int(g));  // z: the spring, w: 1 if i is its i end
      vec4 l = texelFetch(multipliers_view, int(entry.z));
      precise vec3 f = l.xyz * l.w;
      precise vec3 minus = warm - f, plus = warm + f;
      warm = entry.w != 0u ? minus : plus;
    }
  }
  precise vec3 d = predicted_move(displacement_of(i).xyz, material_of(i).keep.x, acc, warm, p.w, params);
  if (params.max_step > 0.0) d = limit_step(d, params.max_step);  // the bounded contact's speed limit
  precise vec3 next = p.xyz + d;
  // The multigrid solve's offset: the external forces' share, which it applies with the
  // springs (predict in host/core/reference/reference_forces.cpp).
  if (MULTIGRID_SOLVER) offset[i] = vec4(solve_start_offset(acc, offset[i].xyz, material_of(i).stiffness.x * p.w, params), 0.0);
  // The tether to the nearest pin (long-range attachments, host/core/cloth/tethers.cpp): xpbd's only,
  // the multigrid solve needs none (docs/solvers.md).
  vec4 tether = MULTIGRID_SOLVER ? vec4(-1.0) : texelFetch(tethers_view, i);
  if (tether.x >= 0.0) {
    precise vec3 e = next - pin_position(int(tether.x));
    precise float limit = params.tether_limit * tether.y;
    tether_to(e, limit, next, d);
  }
  // w: the mass's clearance bound from the meshes, which the sweep's contact list reads
  // (mesh_leaves_alone_after) and every pass up to it keeps; 0 is no bound.
  float clearance = 0.0;
  bool listed = false;
  if (u_collide_objects)
    listed = collider_may_move(i, next, d, clearance);  // compute/contact_list.glsl (list_block appends)
  else if (has_colliders())
    meshes_leave_alone(next, d, clearance);  // the self-contacts collide before the sweep lists
  pos[i] = vec4(next, p.w);
  disp[i] = vec4(d, clearance);
  return listed;
}

void main() {
  int i = int(gl_GlobalInvocationID.x);
  bool listed = i < int(particle_count()) && predict_particle(i);
  if (u_collide_objects) list_block(listed, i);  // (uniform: every invocation reaches it)
}

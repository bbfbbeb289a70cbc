// Reads positions and displacements (through the views), the wind forces, the colliders and
// the last substep's solve offsets; writes positions, displacements and offsets in place. One
// invocation per particle: the fabric solver's first pass (docs/model.md), damped Verlet under
// gravity (and the wind) alone, the springs acting in the multigrid solve after it;
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
// read first: the last substep's offset (solve_start_offset)
layout(std430, binding = BINDING_MG_OFFSET) buffer Offsets { vec4 offset[]; };

uniform bool u_collide_objects;

// Particle i's prediction; true where a collider may move it (listed for collide_objects).
bool predict_particle(int i) {
  vec4 p = position_of(i);
  if (p.w == 0.0) {
    offset[i] = vec4(0.0);
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
  precise vec3 d = predicted_move(displacement_of(i).xyz, material_of(i).keep.x, acc, params);
  if (params.max_step > 0.0) d = limit_step(d, params.max_step);  // the bounded contact's speed limit
  precise vec3 next = p.xyz + d;
  // The multigrid solve's offset: the external forces' share, which it applies with the
  // springs (predict in host/core/reference/reference_forces.cpp).
  offset[i] = vec4(solve_start_offset(acc, offset[i].xyz, material_of(i).stiffness.z * p.w, params), 0.0);
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

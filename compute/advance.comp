// Forces, then damped Verlet, then (with u_collide_objects) the collision objects: steps 1,
// 2 and 4 of docs/design.md §1 for one particle, fused so the force never leaves registers. The
// CPU twin is advance() in host/core/reference/reference.hpp. Reads positions (its own and its
// neighbours') and displacements through the views; writes the new position to the output
// buffer (neighbours still read the old one: ping-pong, the host swaps) and the new
// displacement in place. One invocation per particle; pinned particles (w = 0) stay.
#include "layout.glsl"
#include "common.glsl"
#include "forces.glsl"
#include "collide_objects.glsl"
#include "contact_list.glsl"
#include "pinned_motion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
layout(std430, binding = BINDING_POSITIONS_OUT) writeonly buffer Output { vec4 pos_out[]; };
layout(std430, binding = BINDING_WIND_FORCES) readonly buffer WindForces { vec4 wind_force[]; };

uniform bool u_collide_objects;

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  if (p.w == 0.0) {
    vec4 next;
    vec3 moved;
    if (move_pinned(i, p, next, moved)) disp[i] = vec4(moved, 0.0);
    pos_out[i] = next;
    return;
  }
  vec3 x = p.xyz;
  float mass;
  Material mat = material_and_mass_of(i, mass);
  precise vec3 f = spring_force(i, x, mat, mass);
  if (WIND_ENABLED) f = f + wind_force[i].xyz;  // compute_wind_forces ran before
  precise vec3 d = verlet_move(displacement_of(i).xyz, mat.keep.x, f, p.w, params);
  precise vec3 next = x + d;
  // (The clearance it returns is for the sweeps after predict: the classic step has none.)
  if (u_collide_objects) list_if_collider_may_move(i, next, d);  // compute/contact_list.glsl
  disp[i] = vec4(d, 0.0);
  pos_out[i] = vec4(next, p.w);
}

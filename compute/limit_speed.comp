// The speed clamp's last word (simulation.max_speed; the integration's share is in
// compute/shared/integration.glsl): after the constraints and the contacts, a free mass whose
// substep moved it further than max_move = max_speed * dt goes back along its move to max_move
// from where it started, so that nothing (a fast collider's push, a constraint's jump) moves it
// faster. Runs at the end of every substep of a scene with max_speed above 0 (its row in
// host/gpu/pass_table.hpp). CPU twin: limit_speed in host/core/reference/reference_forces.cpp.
// One invocation per particle; reads and writes its own position and displacement.
#include "layout.glsl"
#include "common.glsl"
#include "shared/integration.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) buffer Displacements { vec4 disp[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  vec4 p = pos[i], d = disp[i];
  if (p.w == 0.0 || !(length3(d.xyz) > params.max_move)) return;
  vec3 x = p.xyz, moved = d.xyz;
  limit_speed_of(x, moved, params.max_move);
  pos[i] = vec4(x, p.w);
  disp[i] = vec4(moved, d.w);
}

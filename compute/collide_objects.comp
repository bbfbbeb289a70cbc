// Reads positions, previous positions and the colliders; writes positions in place. One
// invocation per particle. The step fuses this into advance or collide_self (the particle's
// position makes one trip); this pass stays for the pass-by-pass check against the reference.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  if (p.w == 0.0) return;
  pos[i].xyz = collide_with_objects(p.xyz, previous_of(i).xyz);
}

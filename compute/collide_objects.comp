// Reads positions, displacements and the colliders; writes positions and displacements in
// place. One invocation per particle. The step fuses this into advance or
// resolve_self_contacts (the particle's state makes one trip); this pass stays for the
// pass-by-pass check against the reference.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  if (p.w == 0.0) return;
  vec3 x = p.xyz, d = displacement_of(i).xyz;
  collide_with_objects(x, d);
  pos[i] = vec4(x, p.w);
  disp[i] = vec4(d, 0.0);
}

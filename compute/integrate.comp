// Reads forces, positions, previous positions; writes positions and previous positions in
// place. One invocation per particle (damped Verlet; pinned particles, w = 0, stay put).
// The step runs advance, which fuses this with the forces; this pass stays for the pass checks.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_PREVIOUS) buffer Previous { vec4 prev[]; };
layout(std430, binding = BINDING_FORCES) readonly buffer Forces { vec4 force[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  vec4 p = pos[i];
  if (p.w == 0.0) return;
  vec3 x = p.xyz;
  precise vec3 a = force[i].xyz * p.w;
  precise vec3 next = x + (x - prev[i].xyz) * params.keep_velocity + a * params.dt2;
  prev[i] = p;
  pos[i] = vec4(next, p.w);
}

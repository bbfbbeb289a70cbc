// Reads positions and the gather lists; writes forces. One invocation per particle, gathering
// its own springs (compute/forces.glsl), so no atomics are needed. The step uses advance,
// which keeps the force in registers; this pass stays for the pass-by-pass check.
#include "layout.glsl"
#include "common.glsl"
#include "features.glsl"
#include "forces.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_FORCES) writeonly buffer Forces { vec4 force[]; };
layout(std430, binding = BINDING_WIND_FORCES) readonly buffer WindForces { vec4 wind_force[]; };

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  float mass;
  Material mat = material_and_mass_of(i, mass);
  precise vec3 f = spring_force(i, position_of(i).xyz, mat, mass);
  if (WIND_ENABLED) f = f + wind_force[i].xyz;
  force[i] = vec4(f, 0.0);
}

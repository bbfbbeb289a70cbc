// Reads positions and displacements (of the particle and its neighbours, through the views);
// writes the aerodynamic force per particle. One invocation per particle, gathering its
// triangles' shares (compute/wind.glsl), so no atomics are needed. Runs before advance when
// the scene has wind; advance adds the force to the springs'.
#include "layout.glsl"
#include "common.glsl"
#include "wind.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_WIND_FORCES) writeonly buffer WindForces { vec4 wind_force[]; };

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  wind_force[i] = vec4(gather_wind_force(i), 0.0);
}

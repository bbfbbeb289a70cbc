// Reads positions and displacements (of the particle and its neighbours, through the views);
// writes the aerodynamic force per particle. One invocation per grid point, gathering its
// triangles' shares (compute/wind.glsl), so no atomics are needed. Runs before advance when
// the scene has wind; advance adds the force to the springs'.
#include "layout.glsl"
#include "common.glsl"
#include "wind.glsl"

layout(local_size_x = GRID_WORKGROUP_X, local_size_y = GRID_WORKGROUP_Y) in;
layout(std430, binding = BINDING_WIND_FORCES) writeonly buffer WindForces { vec4 wind_force[]; };

void main() {
  ivec2 c = ivec2(gl_GlobalInvocationID.xy);
  if (!in_grid(c)) return;
  wind_force[grid_index(c)] = vec4(gather_wind_force(c), 0.0);
}

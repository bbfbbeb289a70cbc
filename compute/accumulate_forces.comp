// Reads positions and rest lengths; writes forces. One invocation per grid point, gathering
// its own springs (compute/forces.glsl), so no atomics are needed. The step uses advance,
// which keeps the force in registers; this pass stays for the pass-by-pass check.
#include "layout.glsl"
#include "common.glsl"
#include "forces.glsl"

layout(local_size_x = GRID_WORKGROUP_X, local_size_y = GRID_WORKGROUP_Y) in;
layout(std430, binding = BINDING_FORCES) writeonly buffer Forces { vec4 force[]; };
layout(std430, binding = BINDING_WIND_FORCES) readonly buffer WindForces { vec4 wind_force[]; };

void main() {
  ivec2 c = ivec2(gl_GlobalInvocationID.xy);
  if (!in_grid(c)) return;
  int i = grid_index(c);
  precise vec3 f = spring_force(c, i, position_of(i).xyz);
  if (params.wind_enabled != 0u) f = f + wind_force[i].xyz;
  force[i] = vec4(f, 0.0);
}

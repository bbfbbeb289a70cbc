// Reads the step parameters, writes positions; one invocation per particle.
// Test fixture: the shared layout header compiles as GLSL and a #define overrides WORKGROUP_SIZE.
#include "../../compute/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 positions[]; };
layout(std140, binding = BINDING_STEP_PARAMS) uniform Params { StepParams params; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  positions[i].xyz += params.gravity * params.dt2;
}

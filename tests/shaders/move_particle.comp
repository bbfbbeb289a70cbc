// Moves one particle of the simulation's positions buffer by u_offset, on the GPU. Test
// fixture for tests/test_render.cpp: the renderer must show the move with no CPU upload,
// because its vertex stage reads this very buffer.
#include "../../compute/layout.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 pos[]; };

uniform int u_particle;
uniform vec3 u_offset;

void main() { pos[u_particle].xyz += u_offset; }

// The shadow pass's vertex stage: a caster's vertex (pulled from the SSBOs like every other
// shader) seen from the key light, through the projection fit_shadow_frustum.comp fitted
// to this frame's casters.
#include "../compute/layout.glsl"
#include "vertex_pull.glsl"

layout(std430, binding = BINDING_DRAW_SHADOW) readonly buffer Shadow { ShadowFrame shadow_frame; };

void main() {
  PulledVertex v = pull_vertex(gl_VertexID);
  mat4 vp = mat4(shadow_frame.view_projection[0], shadow_frame.view_projection[1],
                 shadow_frame.view_projection[2], shadow_frame.view_projection[3]);
  gl_Position = vp * (u_model * vec4(v.position, 1.0));
}

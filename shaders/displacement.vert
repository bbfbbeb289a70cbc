// Displacement: moves each vertex along its normal by the height texture (times
// u_height_scaling), then shades like Bump.
#include "../compute/layout.glsl"
#include "vertex_pull.glsl"

uniform sampler2D u_height_texture;
uniform float u_height_scaling;

out vec3 v_position;
out vec3 v_normal;
out vec3 v_tangent;
out vec2 v_uv;

void main() {
  PulledVertex v = pull_vertex(gl_VertexID);
  float h = textureLod(u_height_texture, v.uv, 0.0).r;
  vec4 world = u_model * vec4(v.position + v.normal * (h * u_height_scaling), 1.0);
  v_position = world.xyz;
  v_normal = normalize(mat3(u_model) * v.normal);
  v_tangent = normalize(mat3(u_model) * v.tangent);
  v_uv = v.uv;
  gl_Position = u_view_projection * world;
}

// The vertex stage of every shader but Displacement: pulls a vertex from the SSBOs and
// passes world-space position, normal, tangent and uv on.
#include "../compute/layout.glsl"
#include "vertex_pull.glsl"

out vec3 v_position;
out vec3 v_normal;
out vec3 v_tangent;
out vec2 v_uv;

void main() {
  PulledVertex v = pull_vertex(gl_VertexID);
  vec4 world = u_model * vec4(v.position, 1.0);
  v_position = world.xyz;
  v_normal = normalize(mat3(u_model) * v.normal);
  v_tangent = normalize(mat3(u_model) * v.tangent);
  v_uv = v.uv;
  gl_Position = u_view_projection * world;
}

// Vertex pulling: every render shader reads its vertices straight from the simulation's
// storage buffers by gl_VertexID (the cloth is never copied). Collider meshes use the same
// bindings with their own buffers, plus an extras buffer for uv and tangent.
#ifndef CLOTHSIM_VERTEX_PULL_GLSL
#define CLOTHSIM_VERTEX_PULL_GLSL

layout(std430, binding = BINDING_DRAW_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DRAW_NORMALS) readonly buffer Normals { vec4 normal[]; };
layout(std430, binding = BINDING_DRAW_EXTRAS) readonly buffer Extras { MeshVertex extra[]; };

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform int u_is_cloth;   // 1: uv and tangent from the cloth grid; 0: from the extras buffer
uniform ivec2 u_grid;     // cloth grid size (num_width_points, num_height_points)

struct PulledVertex {
  vec3 position, normal, tangent;
  vec2 uv;
};

PulledVertex pull_vertex(int i) {
  PulledVertex v;
  v.position = pos[i].xyz;
  v.normal = normal[i].xyz;
  if (u_is_cloth == 1) {
    ivec2 c = ivec2(i % u_grid.x, i / u_grid.x);
    v.uv = vec2(c) / vec2(u_grid - 1);
    // Tangent along +x of the grid (+u): a central difference, one-sided at the edges.
    int left = c.x > 0 ? i - 1 : i, right = c.x + 1 < u_grid.x ? i + 1 : i;
    vec3 t = pos[right].xyz - pos[left].xyz;
    t -= v.normal * dot(t, v.normal);
    v.tangent = length(t) > 1e-12 ? normalize(t) : vec3(1.0, 0.0, 0.0);
  } else {
    v.uv = extra[i].uv.xy;
    v.tangent = extra[i].tangent.xyz;
  }
  return v;
}

#endif

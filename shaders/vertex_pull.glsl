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
uniform int u_is_cloth;   // 1: the cloth (tangent from its positions); 0: a collider mesh

struct PulledVertex {
  vec3 position, normal, tangent;
  vec2 uv;
};

PulledVertex pull_vertex(int i) {
  PulledVertex v;
  v.position = pos[i].xyz;
  v.normal = normal[i].xyz;
  if (u_is_cloth == 1) {
    v.uv = extra[i].uv.xy;
    // Tangent along +u: the difference of the particles before and after this one along u
    // (on a grid x - 1 and x + 1, one-sided at the edges), which the cloth carries as it moves.
    int left = int(extra[i].uv.z), right = int(extra[i].uv.w);
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

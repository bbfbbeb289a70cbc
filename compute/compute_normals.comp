// Reads positions; writes normals. One invocation per particle: the area-weighted sum of
// the normals of the triangles around it, normalised (once per rendered frame).
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_NORMALS) writeonly buffer Normals { vec4 normal[]; };

vec3 triangle_normal(int a, int b, int c) {
  vec3 u = pos[b].xyz - pos[a].xyz;
  vec3 v = pos[c].xyz - pos[a].xyz;
  // Unnormalised: its length is twice the area, which is the weight we want.
  precise vec3 n = vec3(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
  return n;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  ivec2 p = grid_coord(i);
  ivec2 size = grid_size();
  precise vec3 sum = vec3(0.0);
  // The up to four cells around p, each split into (A, C, B) and (B, C, D), in reference order.
  for (int cy = p.y - 1; cy <= p.y; ++cy) {
    for (int cx = p.x - 1; cx <= p.x; ++cx) {
      if (cx < 0 || cy < 0 || cx + 1 >= size.x || cy + 1 >= size.y) continue;
      int a = grid_index(ivec2(cx, cy)), b = grid_index(ivec2(cx + 1, cy));
      int c = grid_index(ivec2(cx, cy + 1)), d = grid_index(ivec2(cx + 1, cy + 1));
      int self = int(i);
      if (a == self || c == self || b == self) sum = sum + triangle_normal(a, c, b);
      if (b == self || c == self || d == self) sum = sum + triangle_normal(b, c, d);
    }
  }
  float len = length3(sum);
  precise float inv = 1.0 / len;
  normal[i] = len > 0.0 ? vec4(sum * inv, 0.0) : vec4(0.0, 1.0, 0.0, 0.0);
}

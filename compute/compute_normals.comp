// Reads positions; writes normals. One invocation per particle: the area-weighted sum of
// the normals of the triangles around it (the model's corner lists), normalised (once per
// rendered frame).
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"

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
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  precise vec3 sum = vec3(0.0);
  // The triangles around i, ascending (on a grid: the cells (x-1..x, y-1..y), each split into
  // (A, C, B) and (B, C, D)), in reference order.
  for (uint k = corners_first(i); k < corners_first(i + 1); ++k) {
    ivec3 t = corner_triangle(k);
    sum = sum + triangle_normal(t.x, t.y, t.z);
  }
  float len = length3(sum);
  precise float inv = 1.0 / len;
  normal[i] = len > 0.0 ? vec4(sum * inv, 0.0) : vec4(0.0, 1.0, 0.0, 0.0);
}

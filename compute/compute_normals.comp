// Reads positions; writes normals. One invocation per particle: the area-weighted sum of
// the normals of the triangles around it (the model's corner lists), normalised (once per
// rendered frame).
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_NORMALS) writeonly buffer Normals { vec4 normal[]; };

// Unnormalised: its length is twice the area, which is the weight we want.
vec3 triangle_normal(int a, int b, int c) { return cross3(pos[b].xyz - pos[a].xyz, pos[c].xyz - pos[a].xyz); }

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
  normal[i] = vec4(unit_or_up(sum), 0.0);
}

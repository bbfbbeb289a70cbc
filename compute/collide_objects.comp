// Reads positions, previous positions and the colliders; writes positions in place. One
// invocation per particle: every sphere in file order, then every plane (DESIGN.md §1.4).
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_PREVIOUS) readonly buffer Previous { vec4 prev[]; };
layout(std430, binding = BINDING_SPHERES) readonly buffer Spheres { SphereCollider spheres[]; };
layout(std430, binding = BINDING_PLANES) readonly buffer Planes { PlaneCollider planes[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  vec4 p = pos[i];
  if (p.w == 0.0) return;
  precise vec3 x = p.xyz;
  vec3 xp = prev[i].xyz;
  for (uint s = 0u; s < params.colliders.x; ++s) {
    vec3 o = spheres[s].origin_radius.xyz;
    float r = spheres[s].origin_radius.w;
    vec3 e = x - o;
    float d = length3(e);
    if (d > r) continue;
    precise vec3 t;
    if (d > 0.0) {
      precise float scale = r * (1.0 / d);
      t = o + e * scale;
    } else {
      t = o + vec3(0.0, r, 0.0);  // at the centre there is no outward direction: push up
    }
    x = xp + (t - xp) * spheres[s].keep.x;
  }
  for (uint k = 0u; k < params.colliders.y; ++k) {
    vec3 q = planes[k].point.xyz;
    vec3 n = planes[k].normal.xyz;
    float d = dot3(x - q, n);
    float dp = dot3(xp - q, n);
    precise float crossing = d * dp;
    if (crossing > 0.0) continue;
    float side = dp > 0.0 ? 1.0 : (dp < 0.0 ? -1.0 : 0.0);
    precise float lift = 1e-4 * side;
    precise vec3 t = x - n * d + n * lift;
    x = xp + (t - xp) * planes[k].normal.w;
  }
  pos[i] = vec4(x, p.w);
}

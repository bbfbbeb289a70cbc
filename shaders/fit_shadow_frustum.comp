// Fits the key light's shadow projection to this frame's casters: the cloth, read in place
// from the simulation's positions (no copy to the host), and the colliders' box (from the
// host, which moves them). One workgroup: each invocation folds a strided share of the
// particles, a tree in shared memory joins the shares, and the first invocation writes the
// ShadowFrame the shadow pass and the lit shaders read next. One workgroup is enough: a
// million particles are 16 MB of reads, some tens of microseconds on a GPU, and it needs
// neither atomics nor a clear (and gives the same bits on every run).
#include "../compute/layout.glsl"

#define FIT_THREADS 256
layout(local_size_x = FIT_THREADS) in;

layout(std430, binding = BINDING_DRAW_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DRAW_SHADOW) writeonly buffer Shadow { ShadowFrame shadow_frame; };

uniform int u_count;             // particles
uniform vec3 u_light_position;   // world, m
uniform float u_light_radius;    // m: the disc the soft shadows come from
uniform vec3 u_colliders_lo;     // the spheres' and meshes' box (lo > hi when there are none)
uniform vec3 u_colliders_hi;
uniform float u_map_size;        // texels per side

shared vec3 s_lo[FIT_THREADS];
shared vec3 s_hi[FIT_THREADS];

// A right-handed look-at and a symmetric perspective, as glm::lookAt and glm::perspective
// build them (written out: GLSL has neither).
mat4 look_at(vec3 eye, vec3 centre, vec3 up) {
  vec3 f = normalize(centre - eye), s = normalize(cross(f, up)), u = cross(s, f);
  return mat4(vec4(s.x, u.x, -f.x, 0.0), vec4(s.y, u.y, -f.y, 0.0), vec4(s.z, u.z, -f.z, 0.0),
              vec4(-dot(s, eye), -dot(u, eye), dot(f, eye), 1.0));
}
mat4 perspective(float tan_half, float near, float far) {
  return mat4(vec4(1.0 / tan_half, 0.0, 0.0, 0.0), vec4(0.0, 1.0 / tan_half, 0.0, 0.0),
              vec4(0.0, 0.0, -(far + near) / (far - near), -1.0), vec4(0.0, 0.0, -2.0 * far * near / (far - near), 0.0));
}

void main() {
  const uint me = gl_LocalInvocationIndex;
  vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
  for (int i = int(me); i < u_count; i += FIT_THREADS) {
    vec3 p = pos[i].xyz;
    // A diverged particle (NaN, inf) must not blow the map up; the divergence guard reports it.
    if (any(isnan(p)) || any(isinf(p))) continue;
    lo = min(lo, p);
    hi = max(hi, p);
  }
  s_lo[me] = lo;
  s_hi[me] = hi;
  for (uint half_count = FIT_THREADS / 2; half_count > 0; half_count /= 2) {
    // Everyone's share is in shared memory before the lower half reads the upper one.
    barrier();
    if (me < half_count) {
      s_lo[me] = min(s_lo[me], s_lo[me + half_count]);
      s_hi[me] = max(s_hi[me], s_hi[me + half_count]);
    }
  }
  barrier();
  if (me != 0) return;
  lo = min(s_lo[0], u_colliders_lo);
  hi = max(s_hi[0], u_colliders_hi);
  if (any(greaterThan(lo, hi))) lo = hi = vec3(0.0);  // nothing finite to cast: any small frustum
  const vec3 centre = 0.5 * (lo + hi);
  // The bounding sphere, padded by 2 % and 1 mm so that the outermost caster is not on the
  // map's border, where the soft filter would read past it.
  const float radius = 0.51 * length(hi - lo) + 1e-3;
  vec3 axis = centre - u_light_position;
  float distance_to_centre = length(axis);
  axis = distance_to_centre > 1e-6 ? axis / distance_to_centre : vec3(0.0, -1.0, 0.0);
  // A light inside the casters' sphere would need a cube map; clamping the half angle to
  // about 72 degrees keeps the frustum finite and shadows what lies in front of the light.
  const float sin_half = min(radius / max(distance_to_centre, 1e-6), 0.95);
  const float tan_half = sin_half / sqrt(1.0 - sin_half * sin_half);
  const float far = distance_to_centre + radius;
  const float near = max(distance_to_centre - radius, 0.01 * far);
  const vec3 up = abs(axis.y) > 0.99 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  const mat4 vp = perspective(tan_half, near, far) * look_at(u_light_position, u_light_position + axis, up);
  for (int c = 0; c < 4; ++c) shadow_frame.view_projection[c] = vp[c];
  shadow_frame.light = vec4(u_light_position, u_light_radius);
  shadow_frame.range = vec4(near, far, tan_half, 1.0 / u_map_size);
}

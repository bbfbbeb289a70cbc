// Screen-space ambient occlusion (a normal-oriented hemisphere, after Crytek's SSAO and
// its later forms): how much of the sky a pixel's surface point sees within u_radius,
// estimated from the depth pre-pass. Twelve points in the hemisphere above the surface,
// each occluded when the depth buffer has something in front of it; a range check drops
// occluders much farther away than the radius (a cloth 5 cm above the floor does not darken
// it, one resting on it does). The taps turn by a 4x4 pattern, which blur_ambient.frag's
// 4x4 mean removes.
#include "occlusion_common.glsl"

uniform mat4 u_projection;  // the camera's
uniform float u_radius;     // m

out float out_occlusion;

#define AO_TAPS 12

// A 4x4 ordered pattern: 16 different turns in every 4x4 block.
float bayer4(ivec2 p) {
  const int m[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
  return float(m[(p.y & 3) * 4 + (p.x & 3)]) / 16.0;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(u_depth, px, 0).r;
  if (depth >= 1.0) {  // the background
    out_occlusion = 1.0;
    return;
  }
  vec3 p = view_position(px);
  // The normal from the nearer neighbour on each side, so a depth edge does not tilt it.
  vec3 dx1 = view_position(px + ivec2(1, 0)) - p, dx0 = p - view_position(px - ivec2(1, 0));
  vec3 dy1 = view_position(px + ivec2(0, 1)) - p, dy0 = p - view_position(px - ivec2(0, 1));
  vec3 dx = abs(dx1.z) < abs(dx0.z) ? dx1 : dx0, dy = abs(dy1.z) < abs(dy0.z) ? dy1 : dy0;
  vec3 n = normalize(cross(dx, dy));
  if (dot(n, p) > 0.0) n = -n;  // towards the camera, at the origin of view space
  vec3 helper = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 t = normalize(cross(helper, n)), b = cross(n, t);
  float turn = 6.2831853 * bayer4(px);
  float occluded = 0.0;
  for (int k = 0; k < AO_TAPS; ++k) {
    // Even in solid angle (Fibonacci), nearer taps denser: close occluders matter most.
    float cos_theta = 1.0 - (float(k) + 0.5) / float(AO_TAPS);
    float sin_theta = sqrt(1.0 - cos_theta * cos_theta);
    float phi = float(k) * 2.39996323 + turn;
    float reach = u_radius * mix(0.15, 1.0, pow((float(k) + 1.0) / float(AO_TAPS), 2.0));
    vec3 dir = t * (sin_theta * cos(phi)) + b * (sin_theta * sin(phi)) + n * cos_theta;
    vec3 s = p + (reach * 0.97 + 0.03 * u_radius) * dir;
    vec4 clip = u_projection * vec4(s, 1.0);
    if (clip.w <= 0.0) continue;
    ivec2 spx = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * u_viewport));
    if (any(lessThan(spx, ivec2(0))) || any(greaterThanEqual(spx, ivec2(u_viewport)))) continue;
    float scene_z = view_position(spx).z;
    // Occluded: the surface seen there is in front of the tap (view z grows towards the camera).
    float in_front = step(s.z + 0.02 * u_radius, scene_z);
    // Full weight within the radius, none past twice it: a surface much farther away shades
    // other light, not this point's sky.
    occluded += in_front * clamp(2.0 - abs(p.z - scene_z) / u_radius, 0.0, 1.0);
  }
  out_occlusion = 1.0 - occluded / float(AO_TAPS);
}

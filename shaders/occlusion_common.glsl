// What the occlusion passes share: the depth pre-pass and view-space positions from it.
#ifndef CLOTHSIM_OCCLUSION_COMMON_GLSL
#define CLOTHSIM_OCCLUSION_COMMON_GLSL

uniform sampler2D u_depth;            // unit 0: the pre-pass's depth, one sample per pixel
uniform mat4 u_inverse_projection;    // the camera's, clip -> view
uniform vec2 u_viewport;              // pixels

// The view-space point seen at pixel px (clamped to the viewport).
vec3 view_position(ivec2 px) {
  px = clamp(px, ivec2(0), ivec2(u_viewport) - 1);
  float d = texelFetch(u_depth, px, 0).r;
  vec4 ndc = vec4((vec2(px) + 0.5) / u_viewport * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
  vec4 v = u_inverse_projection * ndc;
  return v.xyz / v.w;
}

#endif

// The key light's shadow: percentage-closer soft shadows (Fernando 2005) from the map the
// shadow pass drew this frame. The light is a disc of radius shadow_frame.light.w facing
// the scene, so a shadow is sharp where the caster touches (a cloth lying on the floor) and
// soft where it is far (a cloth 5 cm above it): a blocker search finds how far the casters
// between p and the light are, their distance sizes the filter, and a filter of compare
// taps averages how much of the disc p sees. Acne is kept off by three things, each for its
// own cause: the shadow pass's slope-scaled polygon offset (the map's own depth quantisation),
// a normal offset of about a texel here (surfaces grazing the light), and a receiver-plane
// depth for every tap from the shading normal, with slack growing with the tap's distance (a
// filter tens of texels wide across a tilted, curved receiver would otherwise shadow the
// receiver with itself).
#ifndef CLOTHSIM_SHADOW_GLSL
#define CLOTHSIM_SHADOW_GLSL

#include "../compute/layout.glsl"

layout(std430, binding = BINDING_DRAW_SHADOW) readonly buffer Shadow { ShadowFrame shadow_frame; };
uniform int u_shadows;                 // 1: the key light casts shadows (render --shadows, the viewer)
uniform sampler2DShadow u_shadow_map;  // unit 3: depth compare, bilinear (each tap a 2x2 PCF)
uniform sampler2D u_shadow_depth;      // unit 4: the same depths, raw (the blocker search)

#define SEARCH_TAPS 8
#define FILTER_TAPS 12

// Tap k of n on the unit disc, Vogel's spiral turned by `angle`: even cover with no table.
vec2 disc_tap(int k, int n, float angle) {
  float r = sqrt((float(k) + 0.5) / float(n));
  float a = float(k) * 2.39996323 + angle;  // the golden angle
  return r * vec2(cos(a), sin(a));
}

// The light's window depth (0..1) as metres along its axis.
float light_distance(float window_z) {
  float n = shadow_frame.range.x, f = shadow_frame.range.y;
  return 2.0 * n * f / (f + n - (2.0 * window_z - 1.0) * (f - n));
}

// The light's axes from its view-projection: rows 0 and 1 are the map's u and v axes over
// tan_half, row 3 (w = depth) is the direction it looks in.
vec3 light_row(int r) {
  return vec3(shadow_frame.view_projection[0][r], shadow_frame.view_projection[1][r], shadow_frame.view_projection[2][r]);
}

// Metres along the light's axis back to a window depth (the inverse of light_distance).
float window_depth(float d) {
  float n = shadow_frame.range.x, f = shadow_frame.range.y;
  return 0.5 * ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * d)) + 0.5;
}

// The receiver plane's depth change at a tap `offset` (uv) away, capped where the plane
// recedes from the light: a surface meeting the light at a grazing angle has a facet plane
// that falls away steeply, and its curved neighbours, falling away less, would shadow p. A
// cap errs towards light (the receiver's own surface is never behind the reference), where
// no cap on the approaching side may miss nothing: that side must stay exact.
float plane_depth(vec2 depth_per_uv, vec2 offset, float texel_world) {
  return min(dot(depth_per_uv, offset), 2.0 * texel_world);
}

// How much of the key light's disc the surface point p with normal n (the side being shaded)
// sees: 1 lit, 0 in full shadow.
float key_light_visibility(vec3 p, vec3 n) {
  if (u_shadows == 0) return 1.0;
  vec3 to_light = shadow_frame.light.xyz - p;
  float dist = length(to_light);
  vec3 l = to_light / max(dist, 1e-9);
  float cos_l = dot(n, l);
  if (cos_l <= 0.0) return 0.0;  // facing away: the light does not reach this side at all
  float texel_uv = shadow_frame.range.w, tan_half = shadow_frame.range.z;
  float texel_world = 2.0 * tan_half * dist * texel_uv;
  // Normal offset: more as the surface turns away from the light, where one texel spans more of it.
  vec3 q = p + n * (texel_world * (0.5 + 1.5 * (1.0 - cos_l)));
  mat4 vp = mat4(shadow_frame.view_projection[0], shadow_frame.view_projection[1],
                 shadow_frame.view_projection[2], shadow_frame.view_projection[3]);
  vec4 clip = vp * vec4(q, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;  // no caster out there
  float receiver = light_distance(min(ndc.z * 0.5 + 0.5, 1.0));
  // The receiver's tangent plane, as metres of depth per unit of uv offset: a step w across
  // the light's axis f meets the plane dot(w, n) / dot(f, n) nearer. Each tap compares with
  // the plane's depth there, not with p's, so a filter tens of texels wide across a tilted
  // receiver does not shadow the receiver with itself.
  vec3 axis_u = normalize(light_row(0)), axis_v = normalize(light_row(1)), forward = normalize(light_row(3));
  float facing = min(dot(forward, n), -0.2);  // it faces the light: dot(forward, n) < 0; steeper is no guide
  vec2 depth_per_uv = -(2.0 * tan_half * receiver) * vec2(dot(axis_u, n), dot(axis_v, n)) / facing;
  // Slack for the neighbouring facets across a fold bent towards the light: a texel and a
  // half of depth, and two texels of the facet's slope (more where the light grazes it).
  float slack = 1.5 * texel_world + 2.0 * length(depth_per_uv) * texel_uv;
  // And for the surface curving towards the light away from p, and the flat facets the map
  // holds departing from the smooth surface the shading normal describes (a wide filter on a
  // hanging cloth reaches many): 30 % of the lateral distance, about 17 degrees of bend.
  float bend = 0.3 * 2.0 * tan_half * receiver;

  float near = shadow_frame.range.x, radius = shadow_frame.light.w;
  // One rotation of the taps per pixel (interleaved gradient noise, Jimenez 2014): banding
  // of the few taps turns into a fine grain instead of copies of the caster's edge.
  float angle = 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));

  // Blockers: the map seen through the cone from p to the light's disc, widest at the near plane.
  float search = clamp(radius * (receiver - near) / (receiver * near * 2.0 * tan_half), 2.0 * texel_uv, 0.1);
  float blocker_sum = 0.0;
  int blockers = 0;
  for (int k = 0; k < SEARCH_TAPS; ++k) {
    vec2 offset = search * disc_tap(k, SEARCH_TAPS, angle);
    float raw = textureLod(u_shadow_depth, uv + offset, 0.0).r;
    float stored = light_distance(raw);
    // Depth 1 is the cleared map: no caster.
    if (raw < 1.0 && stored < receiver + plane_depth(depth_per_uv, offset, texel_world) - slack - bend * length(offset)) {
      blocker_sum += stored;
      ++blockers;
    }
  }
  if (blockers == 0) return 1.0;
  float blocker = blocker_sum / float(blockers);
  // The penumbra's half-width where p is, as a share of the map there (similar triangles).
  float filter_radius = clamp(radius * max(receiver - blocker, 0.0) / (blocker * 2.0 * tan_half * receiver),
                              1.5 * texel_uv, search);
  float lit = 0.0;
  for (int k = 0; k < FILTER_TAPS; ++k) {
    vec2 offset = filter_radius * disc_tap(k, FILTER_TAPS, angle);
    // Below 1, so that a receiver beyond the casters' far plane is lit where the map is clear.
    float reference = min(window_depth(receiver + plane_depth(depth_per_uv, offset, texel_world) - slack - bend * length(offset)), 0.999999);
    lit += texture(u_shadow_map, vec3(uv + offset, reference));
  }
  return lit / float(FILTER_TAPS);
}

#endif

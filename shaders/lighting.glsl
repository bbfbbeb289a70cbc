// Shared lighting terms: one point light (the key, shadowed by shadow.glsl), a fill light
// (uniform ambient, or studio.glsl's sky and ground) darkened by ambient occlusion, and
// Blinn-Phong. Uniform names are the same in every shader (u_camera_position,
// u_light_position, u_light_intensity, u_color).
#ifndef CLOTHSIM_LIGHTING_GLSL
#define CLOTHSIM_LIGHTING_GLSL

#include "shadow.glsl"
#include "studio.glsl"

uniform vec3 u_camera_position;
uniform vec3 u_light_position;
uniform vec3 u_light_intensity;
uniform vec4 u_color;
uniform sampler2D u_texture;      // colour texture (Texture), unit 0
uniform samplerCube u_environment;  // sky cube map (Mirror), unit 2

in vec3 v_position;
in vec3 v_normal;
in vec3 v_tangent;
in vec2 v_uv;

out vec4 out_color;

// The cloth is two-sided: light the side facing the camera, so the back of a fold is not black.
vec3 facing_normal(vec3 n) {
  return gl_FrontFacing ? normalize(n) : -normalize(n);
}

uniform int u_is_cloth;       // 1: the cloth (the back tint applies), 0: a collider
uniform vec3 u_back_tint;     // multiplies the albedo of the cloth's back (gl_FrontFacing false)
uniform int u_ao;             // 1: the fill light is darkened by ambient occlusion
uniform sampler2D u_ambient_occlusion;  // unit 5: blur_ambient.frag's result, one texel per pixel

// How much of the fill light reaches this pixel (1 with occlusion off).
float ambient_occlusion() {
  return u_ao == 1 ? texelFetch(u_ambient_occlusion, ivec2(gl_FragCoord.xy), 0).r : 1.0;
}

// The albedo as lit: the studio's pattern on the floor, the back tint on the cloth's back.
vec3 surface_albedo(vec3 albedo) {
  if (u_is_floor == 1) return floor_albedo(v_uv);
  if (u_is_cloth == 1 && !gl_FrontFacing) return albedo * u_back_tint;
  return albedo;
}

// The key light's share that reaches p, shadows and (half of) the occlusion included:
// occlusion is strictly a fill-light term, but a crease in full light would then not read at
// all, so half of it darkens the key too, as production renderers let artists choose.
float key_light_share(vec3 n) {
  return key_light_visibility(v_position, n) * mix(1.0, ambient_occlusion(), 0.5);
}

// Irradiance of the point light at p (inverse-square falloff).
vec3 light_irradiance(vec3 p) {
  vec3 d = u_light_position - p;
  return u_light_intensity / max(dot(d, d), 1e-6);
}

// Diffuse has no fill in the classic look (a shadowed side is black); the studio gives it one.
vec3 lambert(vec3 n, vec3 albedo) {
  albedo = surface_albedo(albedo);
  vec3 l = normalize(u_light_position - v_position);
  vec3 fill = studio_fill(n, 0.0) * ambient_occlusion();
  return albedo * light_irradiance(v_position) * (max(dot(n, l), 0.0) * key_light_share(n)) + albedo * fill;
}

vec3 blinn_phong(vec3 n, vec3 albedo, float ks, float shininess) {
  albedo = surface_albedo(albedo);
  if (u_is_floor == 1) ks = 0.05;  // a matte floor: the cloth's highlight would glare on it
  vec3 l = normalize(u_light_position - v_position);
  vec3 v = normalize(u_camera_position - v_position);
  vec3 h = normalize(l + v);
  vec3 irradiance = light_irradiance(v_position) * key_light_share(n);
  vec3 ambient = studio_fill(n, 0.12) * ambient_occlusion() * albedo;
  vec3 diffuse = albedo * irradiance * max(dot(n, l), 0.0);
  vec3 specular = ks * irradiance * pow(max(dot(n, h), 0.0), shininess);
  return ambient + diffuse + specular;
}

// Normal perturbed by the height texture's gradient in tangent space (Bump, Displacement).
uniform sampler2D u_height_texture;
uniform float u_normal_scaling;
uniform float u_height_scaling;
uniform vec2 u_texture_size;  // height texture size in texels

vec3 bumped_normal(vec3 n) {
  vec3 t = normalize(v_tangent - n * dot(v_tangent, n));
  vec3 b = cross(n, t);
  float h = texture(u_height_texture, v_uv).r;
  float hu = texture(u_height_texture, v_uv + vec2(1.0 / u_texture_size.x, 0.0)).r;
  float hv = texture(u_height_texture, v_uv + vec2(0.0, 1.0 / u_texture_size.y)).r;
  // Per-texel height differences scaled by u_normal_scaling give the slope (the classic
  // formulation scales by the height scale too, which makes bumps invisible at sane values).
  float du = (hu - h) * u_normal_scaling;
  float dv = (hv - h) * u_normal_scaling;
  vec3 local = normalize(vec3(-du, -dv, 1.0));
  return normalize(mat3(t, b, n) * local);
}

// The display transform of every lit shader: exposure, a filmic shoulder, gamma 2.2 (the
// inverse of the decoding of sRGB texels in texture.frag and mirror.frag).
uniform float u_exposure;  // Appearance::exposure, render --exposure

// Identity up to the knee, so mid-tones look as they would untouched; above it an exponential
// shoulder with slope 1 at the knee that approaches 1 without reaching it. A clamp would turn
// cloth facing the light (irradiance above 1) flat white and hide Bump's weave; this keeps
// its shading, compressed. Per channel: the brightest highlights desaturate towards white.
vec3 tone_map(vec3 c) {
  const float knee = 0.8;
  vec3 over = max(c - knee, 0.0);
  return min(c, knee) + (1.0 - knee) * (1.0 - exp(-over / (1.0 - knee)));
}

vec4 encode_display(vec3 linear) {
  vec3 display = pow(tone_map(max(linear * u_exposure, 0.0)), vec3(1.0 / 2.2));
  // The floor fades into the background it stands in front of.
  if (u_is_floor == 1) display = mix(display, studio_background(gl_FragCoord.xy), floor_fade(v_uv));
  return vec4(display, u_color.a);
}

#endif

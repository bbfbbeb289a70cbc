// The studio around the cloth: a background gradient, a floor that reads as a floor at any
// scale, and a sky-and-ground fill light. With u_studio 0 the classic look: a flat
// background (Renderer::draw clears to it) and a uniform ambient of 0.12.
#ifndef CLOTHSIM_STUDIO_GLSL
#define CLOTHSIM_STUDIO_GLSL

uniform int u_studio;          // 1: the studio look (render --studio, the viewer)
uniform vec2 u_viewport;       // pixels
uniform int u_is_floor;        // 1: this draw is the floor (a plane collider, or render --floor)
uniform float u_floor_half;    // m, half the side of the drawn floor square (its uv is in metres, 0 .. 2 half)
uniform float u_grid;          // m between the floor's fine lines

// Display values (already encoded): light grey-blue above, darker below, a little darker
// still towards the corners, so the eye reads depth behind the cloth.
vec3 studio_background(vec2 frag) {
  vec2 s = frag / u_viewport;
  vec3 c = mix(vec3(0.12, 0.125, 0.14), vec3(0.36, 0.38, 0.42), smoothstep(0.0, 1.0, s.y));
  return c * (1.0 - 0.35 * dot(s - 0.5, s - 0.5));
}

// 1 on a line of the grid of unit spacing in `coord`, 0 between, anti-aliased by the lines'
// footprint on screen; lines closer than a couple of pixels fade out instead of aliasing.
float grid_lines(vec2 coord) {
  vec2 w = max(fwidth(coord), vec2(1e-6));
  vec2 d = abs(fract(coord - 0.5) - 0.5) / w;
  float on = 1.0 - min(min(d.x, d.y), 1.0);
  return on * (1.0 - smoothstep(0.15, 0.5, max(w.x, w.y)));
}

// The floor's albedo at uv: light grey, fine lines every u_grid and bolder ones every 5.
vec3 floor_albedo(vec2 uv) {
  vec2 m = uv - vec2(u_floor_half);  // metres from the floor's centre, under the cloth
  float fine = grid_lines(m / u_grid), bold = grid_lines(m / (5.0 * u_grid));
  return vec3(0.46, 0.465, 0.47) * (1.0 - 0.16 * fine - 0.22 * bold);
}

// How far the floor has faded into the background: 0 under the cloth, 1 at the square's
// edge, so the floor has no visible end.
float floor_fade(vec2 uv) {
  return smoothstep(0.35, 0.95, length(uv - vec2(u_floor_half)) / u_floor_half);
}

// The fill light's irradiance for a surface facing n: a brighter sky above, a dim bounce
// from below (studio), or the classic uniform ambient.
vec3 studio_fill(vec3 n, float classic) {
  return u_studio == 1 ? mix(vec3(0.07), vec3(0.22), 0.5 + 0.5 * n.y) : vec3(classic);
}

#endif

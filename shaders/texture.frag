// Texture: the colour texture mapped by uv, lit diffusely so the folds still read.
#include "lighting.glsl"


void main() {
  vec3 albedo = pow(texture(u_texture, v_uv).rgb, vec3(2.2));  // sRGB texels to linear
  out_color = encode_display(blinn_phong(facing_normal(v_normal), albedo, 0.1, 16.0));
}

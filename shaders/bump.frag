// Bump: Blinn-Phong with the normal perturbed by the height texture (tangent space).
#include "lighting.glsl"

void main() {
  vec3 n = bumped_normal(facing_normal(v_normal));
  out_color = encode_display(blinn_phong(n, u_color.rgb, 0.4, 32.0));
}

// Displacement: the vertices were moved by the height texture (displacement.vert); shade
// like Bump so the fine detail between vertices still shows.
#include "lighting.glsl"

void main() {
  vec3 n = bumped_normal(facing_normal(v_normal));
  out_color = encode_display(blinn_phong(n, u_color.rgb, 0.4, 32.0));
}

// Phong: Blinn-Phong, ambient + diffuse + specular.
#include "lighting.glsl"

void main() { out_color = encode_display(blinn_phong(facing_normal(v_normal), u_color.rgb, 0.5, 16.0)); }

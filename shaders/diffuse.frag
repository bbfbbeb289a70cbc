// Diffuse: Lambertian reflection of one point light.
#include "lighting.glsl"

void main() { out_color = encode_display(lambert(facing_normal(v_normal), u_color.rgb)); }

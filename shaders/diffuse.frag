// Diffuse: Lambertian reflection of one point light.
#include "lighting.glsl"

void main() { out_color = gamma_encode(lambert(facing_normal(v_normal), u_color.rgb)); }

// Mirror: the environment cube map seen by reflection, through the same display transform
// as the lit shaders (so --exposure brightens it too).
#include "lighting.glsl"

void main() {
  vec3 n = facing_normal(v_normal);
  vec3 view = normalize(v_position - u_camera_position);
  vec3 r = reflect(view, n);
  out_color = encode_display(pow(texture(u_environment, r).rgb, vec3(2.2)));  // sRGB texels to linear
}

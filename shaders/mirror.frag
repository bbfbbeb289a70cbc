// Mirror: the environment cube map seen by reflection.
#include "lighting.glsl"


void main() {
  vec3 n = facing_normal(v_normal);
  vec3 view = normalize(v_position - u_camera_position);
  vec3 r = reflect(view, n);
  out_color = vec4(texture(u_environment, r).rgb, 1.0);
}

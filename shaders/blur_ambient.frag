// The 4x4 mean of occlude_ambient.frag's result (which removes its 4x4 pattern of turns),
// over the pixels on the same surface only: a neighbour more than u_radius / 2 deeper or
// nearer is another surface, and its occlusion does not bleed across the edge.
#include "occlusion_common.glsl"

uniform sampler2D u_occlusion;  // unit 1
uniform float u_radius;         // m

out float out_occlusion;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  float z = view_position(px).z;
  float sum = 0.0, weight = 0.0;
  for (int j = -2; j < 2; ++j)
    for (int i = -2; i < 2; ++i) {
      ivec2 q = clamp(px + ivec2(i, j), ivec2(0), ivec2(u_viewport) - 1);
      float w = abs(view_position(q).z - z) < 0.5 * u_radius ? 1.0 : 0.0;
      sum += w * texelFetch(u_occlusion, q, 0).r;
      weight += w;
    }
  out_occlusion = weight > 0.0 ? sum / weight : 1.0;
}

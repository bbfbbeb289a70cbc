// Normal: the surface normal as colour, (n + 1) / 2.
#include "lighting.glsl"

void main() { out_color = vec4(facing_normal(v_normal) * 0.5 + 0.5, 1.0); }

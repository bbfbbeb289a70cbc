// The studio's background gradient, drawn first behind everything.
#include "studio.glsl"

out vec4 out_color;

void main() { out_color = vec4(studio_background(gl_FragCoord.xy), 1.0); }

// Wireframe: the springs (or triangle edges) as flat-coloured lines.
#include "lighting.glsl"

void main() { out_color = u_color; }

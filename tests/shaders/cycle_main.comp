// Test fixture: includes a file that, through another, includes itself.
#include "cycle_a.glsl"
void main() {}

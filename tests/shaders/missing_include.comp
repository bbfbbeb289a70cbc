// Test fixture: includes a file that does not exist.
#include "no_such_file.glsl"
void main() {}

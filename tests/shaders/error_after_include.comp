// Test fixture: the error is at line 10 of this file, after includes that were skipped.
#include "helpers.glsl"
#include "helpers.glsl"
#ifdef NOT_DEFINED
#include "helpers.glsl"
#endif
layout(local_size_x = 1) in;

void main() {
  float y = ) twice(1.0);
}

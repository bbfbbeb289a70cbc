// Test fixture: a guarded include.
#ifndef HELPERS_GLSL
#define HELPERS_GLSL
float twice(float x) { return 2.0 * x; }
#endif

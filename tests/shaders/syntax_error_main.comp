// Test fixture: the error is in the included file, at its line 5.
layout(local_size_x = 1) in;
#include "syntax_error_included.glsl"

void main() { broken(); }

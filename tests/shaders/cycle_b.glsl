// Test fixture: the other half of an include cycle.
#include "cycle_a.glsl"

// Helpers every pass shares, written in exactly the operation order of the C++ reference
// (host/core/reference/reference.hpp) so that llvmpipe and the reference round identically.
// `precise` forbids the compiler from fusing a*b+c into an FMA, which rounds differently.
#ifndef CLOTHSIM_COMMON_GLSL
#define CLOTHSIM_COMMON_GLSL

layout(std140, binding = BINDING_STEP_PARAMS) uniform StepParamsBlock { StepParams params; };

float length3(vec3 v) {
  precise float s = v.x * v.x + v.y * v.y + v.z * v.z;
  return sqrt(s);
}

float dot3(vec3 a, vec3 b) {
  precise float s = a.x * b.x + a.y * b.y + a.z * b.z;
  return s;
}

uint particle_count() { return params.count; }

#endif

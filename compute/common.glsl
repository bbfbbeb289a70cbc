// What every pass shares: the step's parameters, the substep's control (pin_offset, gust_phase),
// and the vector helpers written once for both backends (shared/vector.glsl).
#ifndef CLOTHSIM_COMMON_GLSL
#define CLOTHSIM_COMMON_GLSL

#include "shared/vector.glsl"

layout(std140, binding = BINDING_STEP_PARAMS) uniform StepParamsBlock { StepParams params; };
layout(std140, binding = BINDING_SUBSTEP_CONTROL) uniform SubstepControlBlock { SubstepControl control; };

uint particle_count() { return params.count; }

#endif

// One invocation before each watched pass of enforce_stretch_limit (docs/model.md, xpbd step 6):
// whether the pass runs. A settling pass runs only while the pass before it found a spring over
// its limit (StretchControl's x, set by solve_length_constraints compiled with STRETCH_SETTLED);
// the first watched pass always runs. Writes each colour's indirect dispatch, the colour's
// workgroups or none, so a settled substep skips the rest with no read-back to the host; clears
// the flag for the pass it arms; counts the settling passes run. The CPU twin is
// arm_stretch_pass in host/core/reference/reference.hpp.
#include "layout.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = BINDING_STRETCH_CONTROL) buffer Control {
  StretchControl control;
  StretchDispatch colours[];
};

uniform bool u_first_watched;  // the last fixed pass (or the one with none fixed): it runs

void main() {
  bool go = u_first_watched || control.state.x != 0u;
  control.state.x = 0u;
  if (go && !u_first_watched) control.state.y += 1u;
  for (int c = 0; c < colours.length(); ++c) colours[c].groups.x = go ? colours[c].groups.w : 0u;
}

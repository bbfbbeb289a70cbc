// Reads positions and displacements (through the views) and the first level's corrections;
// writes positions, displacements and the offsets. One invocation per particle: its parents'
// corrections, weighted, moved by (x and d alike, x - d stays the previous position), and kept
// as x - y for the sweep's inertia. The CPU twin is prolong_to_cloth in
// host/core/reference/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
layout(std430, binding = BINDING_MG_OFFSET) writeonly buffer Offsets { vec4 offset[]; };

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  vec3 off = offset_of(i);
  precise vec3 start = p.xyz + off;
  g_self = i;
  bool touching = has_colliders() && touches_colliders(start);
  precise vec3 e = vec3(0.0);
  if (p.w != 0.0 && !touching) {
    uint first = texelFetch(mg_fine_view, i).x, last = texelFetch(mg_fine_view, i + 1).x;
    for (uint k = first; k < last; ++k) {
      uvec4 q = mg_entry(k);  // x the parent, y its weight's bits
      e = e + texelFetch(mg_corr_view, int(q.x)).xyz * uintBitsToFloat(q.y);
    }
  }
  // From the prediction to the start (the offset predict left) plus the correction.
  precise vec3 x = (p.xyz + off) + e;
  vec4 before = displacement_of(i);
  precise vec3 d = (before.xyz + off) + e;
  precise vec3 moved = off + e;
  // Only xyz: every w stays (the inverse mass, predict's clearance bound as x - d stays, the
  // offset's 0), and llvmpipe stores a storage buffer's vector component by component.
  pos[i].xyz = x;
  disp[i].xyz = d;
  offset[i].xyz = moved;
}

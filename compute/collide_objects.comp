// Reads positions, displacements and the colliders; writes positions and displacements in
// place. One invocation per particle; compiled with LISTED, one per mass of the contact list
// (compute/contact_list.glsl): the step's own use, after advance or predict listed them
// (fabric's relax_vertices pushes out inline). Compiled
// without, one per particle: the pass checks' own. With self-collision the step fuses it into
// resolve_self_contacts instead (the particle's state makes one trip).
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "contact_list.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };

void main() {
#ifdef LISTED
  // The masses advance or predict listed (compute/contact_list.glsl), one invocation each.
  if (gl_GlobalInvocationID.x >= contacts.header.w) return;
  int i = int(contacts.entries[gl_GlobalInvocationID.x]);
#else
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
#endif
  vec4 p = position_of(i);
  if (p.w == 0.0) return;
  vec4 moved = displacement_of(i);
  vec3 x = p.xyz, d = moved.xyz;
  g_self = i;  // a skinned collider's nearest triangle: searched for by the substep's first
  g_search = true;  // collision (the listed one after advance or predict), reused by the later ones
  collide_with_objects(x, d);
  // Only xyz: w (the inverse mass; predict's clearance bound, which stays with x - d) is
  // unchanged, and llvmpipe stores a storage buffer's vector component by component.
  pos[i].xyz = x;
  disp[i].xyz = d;
}

// The contact list (docs/performance.md, "The contact list"): advance and predict, and each
// colour of xpbd's and multigrid's sweeps, append the masses that may_collide says a collider
// could move, and collide_objects then runs on those alone, one indirect dispatch for as many
// as there are. llvmpipe runs every branch of a shader for
// every invocation, so the sphere's and the plane's full response cost every mass of the cloth
// when called inline, touching or not; a mass that is not listed is not dispatched at all. The
// result is the same bits: a mass may_collide passes over would leave collide_with_objects at
// its first test, unchanged. Every collider has such a test (spheres, planes and meshes), so
// every pass with colliders lists. The host clears the header before each appending pass.
#ifndef CLOTHSIM_CONTACT_LIST_GLSL
#define CLOTHSIM_CONTACT_LIST_GLSL

#include "layout.glsl"
#include "features.glsl"
#include "collide_objects.glsl"

layout(std430, binding = BINDING_CONTACT_LIST) buffer ContactList {
  uvec4 header;     // ContactListHeader: xyz glDispatchComputeIndirect's workgroups, w the masses listed
  uint entries[];   // the masses' indices, in no particular order
} contacts;

// Appends mass i: its slot, and the workgroups that cover every slot so far.
void list_contact(int i) {
  uint k = atomicAdd(contacts.header.w, 1u);
  contacts.entries[k] = uint(i);
  atomicMax(contacts.header.x, k / uint(WORKGROUP_SIZE) + 1u);
}

// Mass i at x, moved by d, at the end of its pass: listed for collide_objects after the pass
// where a collider may move it (with `friction`: advance and predict; without: the push-out
// after a sweep's correction). The same bits as the response inline.
void list_if_collider_may_move(int i, vec3 x, vec3 d, bool friction) {
  if (may_collide(x, d, friction)) list_contact(i);
}

// The same for a spring's two ends after a sweep's correction (no friction), a pinned end
// (`free` false) never listed.
void list_ends_if_collider_may_move(int i, vec3 xi, vec3 di, int j, vec3 xj, vec3 dj, bvec2 free) {
  bvec2 may = may_collide_pair(xi, di, xj, dj, false);
  if (may.x && free.x) list_contact(i);
  if (may.y && free.y) list_contact(j);
}

#endif

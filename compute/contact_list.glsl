// The contact list (docs/performance.md, "The contact list"): advance and predict append the
// masses that may_collide says a collider could move, and collide_objects then runs on those alone, one indirect dispatch for as many
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

// The indirect dispatch covers slot k: its workgroups reach that far.
void cover_slot(uint k) { atomicMax(contacts.header.x, k / uint(WORKGROUP_SIZE) + 1u); }

// Appends mass i: its slot, and the workgroups that cover every slot so far.
void list_contact(int i) {
  uint k = atomicAdd(contacts.header.w, 1u);
  contacts.entries[k] = uint(i);
  cover_slot(k);
}

// Whether a collider may move mass i at x, moved by d, at the end of advance or predict
// (may_collide, with friction), and its clearance bound.
bool collider_may_move(int i, vec3 x, vec3 d, out float clearance) {
  g_self = i;  // (a skinned collider's slot is cleared where it leaves the mass alone)
  return may_collide(x, d, true, clearance);
}

// Mass i at x, moved by d, at the end of advance or predict: listed for collide_objects (with
// friction) where a collider may move it. Returns the mass's clearance bound (may_collide) for
// its displacement's w, which the later passes of the substep keep.
float list_if_collider_may_move(int i, vec3 x, vec3 d) {
  float clearance;
  if (collider_may_move(i, x, d, clearance)) list_contact(i);
  return clearance;
}

// A workgroup's listed masses as one block of the list, in no particular order within it (one
// atomicAdd on the header a workgroup): the masses a block holds are neighbours in the cloth,
// so the lanes that collide_objects then runs side by side search the same part of a skinned
// collider's tree, where masses appended one by one from two threads' workgroups interleave.
// Called by every invocation of the workgroup, in uniform control flow (it has barriers).
shared uint g_listed_count, g_listed_base;
void list_block(bool listed, int i) {
  if (gl_LocalInvocationIndex == 0u) g_listed_count = 0u;
  barrier();  // (the count is zeroed before any invocation adds to it)
  uint slot = listed ? atomicAdd(g_listed_count, 1u) : 0u;
  barrier();  // (every invocation has added before the first reserves the block)
  if (gl_LocalInvocationIndex == 0u && g_listed_count > 0u) {
    g_listed_base = atomicAdd(contacts.header.w, g_listed_count);
    cover_slot(g_listed_base + g_listed_count - 1u);
  }
  barrier();  // (the block's base is set before the invocations write their entries)
  if (listed) contacts.entries[g_listed_base + slot] = uint(i);
}

#endif

// The reference's skinned mesh colliders (reference_skinning.cpp; docs/model.md, "Skinned and
// animated colliders"): the twins of the skinning passes, and a mass's frame.
#pragma once

#include "reference/reference.hpp"

namespace clothsim {

// skin_colliders and fit_collider_boxes are the CPU twins of compute/skin_colliders.comp (every
// skinned vertex from the palette) and compute/fit_collider_boxes.comp (each group's clusters'
// boxes, then the group's), run by the CPU backend after set_substep_time.
template <class R> void skin_colliders(Control<R>& control, const Constants<R>& c);
template <class R> void fit_collider_boxes(Control<R>& control, const Constants<R>& c);

// A mass meets a skinned collider through its nearest triangle (docs/model.md, "Skinned and
// animated colliders"), which the substep's first collision (collide_objects, with `search`)
// looks for and every later one of the substep reuses (the sweeps' push-outs, the multigrid
// solve's contact test): `slots` are the mass's State::nearest entries (one per skinned
// collider). search: the least (distance, index) within reach, started from the slot's
// triangle (found the same without it, only sooner), kept in the slot. Otherwise: the slot's
// triangle, none where it holds none. Null slots (no state): a search, kept nowhere.
// skinned_mesh_at gives the mass at x (moved d) that triangle's frame (skinned_frame in
// compute/shared/skinning.glsl); false where there is none.
template <class R> bool skinned_mesh_at(const Constants<R>& c, const MeshColliderT<R>& m, const Vec3<R>& x,
                                        const Vec3<R>& d, MeshColliderT<R>& frame, uint32_t* slots, bool search);
// Mesh collider m as it meets a mass at x that moved by d: m itself when rigid, its frame at x
// (in `scratch`) when skinned, null where a skinned one has no triangle for it.
template <class R> const MeshColliderT<R>* mesh_at(const Constants<R>& c, const MeshColliderT<R>& m, const Vec3<R>& x,
                                                   const Vec3<R>& d, MeshColliderT<R>& scratch, uint32_t* slots,
                                                   bool search) {
  if (m.skin.y == 0) return &m;
  return skinned_mesh_at(c, m, x, d, scratch, slots, search) ? &scratch : nullptr;
}
// The mass's slots in `s` (null without them: a state made without the constants' skins).
template <class R> uint32_t* skin_slots(const Constants<R>& c, State<R>& s, uint32_t i) {
  return s.nearest.empty() ? nullptr : &s.nearest[size_t(i) * c.skin_meshes];
}

}  // namespace clothsim

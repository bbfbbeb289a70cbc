// The skinned colliders' per-mass records (BINDING_NEAREST, compute/layout.glsl; docs/model.md,
// "Skinned and animated colliders"). Three sections of one uint buffer:
// - slots [0, S), S = particles * skin_meshes: each mass's nearest triangle of its last search
//   (0xFFFFFFFF none), which the substep's later collisions reuse; part of the state.
// - far records [S, 5 S), 4 per slot: where the mass was when its last search found nothing
//   (xyz) and a lower bound on its distance to every triangle then, plus the skinned vertices'
//   summed moves at that time (w): while the mass and the surface have not moved together
//   further than that bound less the reach, no triangle can be within its reach, and predict
//   leaves it alone without a walk of the tree (far_from_skin). GPU only (the reference searches
//   every mass; the result is the same): zeroed, so void, whenever the state is uploaded.
// - 5 S: the sum of the substeps' largest vertex moves so far (a float's bits; skin_colliders
//   adds the last substep's), 5 S + 1: this substep's (fit_collider_boxes, the largest of its
//   roots', by atomicMax on the bits of a float that is never negative).
#ifndef CLOTHSIM_NEAREST_GLSL
#define CLOTHSIM_NEAREST_GLSL

layout(std430, binding = BINDING_NEAREST) buffer Nearest { uint nearest[]; };
// How much wider than the reach, in node spacings, a search that finds nothing looks, so that its
// record holds the mass off for the substeps in which the two move less than that together.
#define SKIN_FAR_MARGIN 1.0

uint nearest_slots() { return max(1u, params.count * params.skin_meshes); }
uint far_record_at(uint slot) { return nearest_slots() + 4u * slot; }
uint skin_moved_at() { return 5u * nearest_slots(); }
uint skin_motion_at() { return skin_moved_at() + 1u; }
float skin_motion() { return uintBitsToFloat(nearest[skin_motion_at()]); }
// The summed moves through this substep (after fit_collider_boxes).
float skin_moved() {
  precise float moved = uintBitsToFloat(nearest[skin_moved_at()]) + skin_motion();
  return moved;
}

#endif

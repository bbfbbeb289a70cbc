// Self-collision's push-out (docs/design.md §1.3, docs/model.md "Self-contact that holds"): one
// neighbour's share and the average over them. Included by compute/resolve_self_contacts.comp and
// host/core/reference/reference_collisions.cpp; the walk over the hashed grid stays with each
// backend.
#ifndef CLOTHSIM_SHARED_SELF_CONTACT_GLSL
#define CLOTHSIM_SHARED_SELF_CONTACT_GLSL

#include "vector.glsl"

SHARED_BEGIN

// sum plus the push of mass i away from a neighbour at e = xi - xj, d = |e| < keep: out to
// `keep`, the contact distance (share 1: the classic contact) or, bounded, the lesser of it and
// the pair's rest distance, each of the pair moving half the gap (share 0.5).
SHARED_FN VEC3 add_self_contact(VEC3 sum, VEC3 e, REAL d, REAL keep, REAL share) {
  PRECISE REAL push = (keep - d) * (share / d);
  PRECISE VEC3 next = sum + e * push;
  return next;
}

// The scale of the summed push-outs of `hits` contacts: their average, spread over the substeps
// (classic), or whole every substep (bounded).
SHARED_FN REAL self_contact_scale(uint hits, bool bounded, REAL steps) {
  PRECISE REAL classic_scale = REAL(1) / (REAL(hits) * steps);
  PRECISE REAL bounded_scale = REAL(1) / REAL(hits);
  return bounded ? bounded_scale : classic_scale;
}

// The bounded contact's distance for a pair at rest positions ri, rj: the contact distance, or
// their rest distance where that is less (the cloth's own neighbours; docs/model.md).
SHARED_FN REAL bounded_keep(VEC3 ri, VEC3 rj, REAL contact) {
  PRECISE VEC3 rest_e = ri - rj;
  return min(contact, length3(rest_e));
}

// Whether a pair at rest positions ri, rj may take the sweep's contact: only if farther apart at
// rest than the contact distance. A pair no farther apart is in contact at rest (the test heap's
// neighbours at 65², thickness half the spacing, are at exactly the contact distance): the
// cloth's own neighbours, which bounded_keep keeps at their rest distance. In the push-out that
// only undoes a crossing, but as the sweep's penalty it would make every such spring
// SELF_CONTACT_STIFFNESS times stiffer the moment it shortens, and a crumpling cloth, unable to
// compress, stretched past its limit (heap256: 1.105 at frame 9, 1.091 without; docs/model.md).
// Their springs and the push-out keep them apart.
SHARED_FN bool apart_at_rest(VEC3 ri, VEC3 rj, REAL contact) {
  PRECISE VEC3 rest_e = ri - rj;
  return length3(rest_e) > contact;
}

// How far the sweep's contact keeps a pair (`start_e`: the pair's difference where the substep
// began, x - d at each end): the contact distance, or the distance it started at if that was
// less. The sweep only stops a pair from closing; it does not part one, which the push-out
// before it did: a penalty that parts a pair in one substep turns the depth into speed (a
// 65² heap with the contact distance one spacing rose again from 8 cm to 27 cm mean height at
// 1-2 m/s, every layer bouncing on the one below; docs/model.md).
SHARED_FN REAL sweep_contact_keep(VEC3 start_e, REAL contact) {
  return min(contact, length3(start_e));
}

// The sweep's self-contact (relax_vertices, fabric's only, with self-collision): a penalty
// spring of stiffness SELF_CONTACT_STIFFNESS times the mass's own ks pushing it out to `keep`
// (sweep_contact_keep) from a mass of another colour that is apart_at_rest (docs/model.md,
// "Self-contact in the sweep"). Its force joins f and its Hessian k n n^T the 3x3 block, so the
// Newton step weighs the contact against the springs instead of undoing a push-out made before
// the solve.
#define SELF_CONTACT_STIFFNESS 10.0
SHARED_FN VEC3 add_self_contact_pull(VEC3 f, VEC3 e, REAL d, REAL keep, REAL k, OUT(VEC3) n) {
  PRECISE REAL inv = REAL(1) / d;
  n = e * inv;
  PRECISE REAL push = k * (keep - d);
  PRECISE VEC3 next = f + n * push;
  return next;
}

SHARED_END

#endif

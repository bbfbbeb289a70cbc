// Skinned mesh colliders (docs/model.md, "Skinned and animated colliders"): linear blend
// skinning of a vertex, the nearest point of a triangle, and the frame a mass takes from its
// nearest skinned triangle. Included by compute/skin_colliders.comp, compute/collide_meshes.glsl
// and host/core/reference/reference_skinning.cpp; the loops over bones, clusters and triangles,
// and the reads, stay with each backend.
//
// A skinned collider collides through its bind pose's field (mesh_field.glsl): a mass at x is
// carried into the bind pose by the rigid motion that takes its nearest triangle's frame (an
// edge, the normal) there, the nearest point to its bind-pose place; the field answers there.
// At the surface that is the exact distance along the normal, and a hole keeps the winding
// number's sign, whatever the pose.
#ifndef CLOTHSIM_SHARED_SKINNING_GLSL
#define CLOTHSIM_SHARED_SKINNING_GLSL

#include "mesh_field.glsl"

SHARED_BEGIN

// sum + w (L r + t): one bone of a vertex (rows: L's rows, w the translation), bones in slot order.
SHARED_FN VEC3 add_bone(VEC3 sum, REAL w, VEC4 row0, VEC4 row1, VEC4 row2, VEC3 r) {
  PRECISE REAL x = ((row0.x * r.x + row0.y * r.y) + row0.z * r.z) + row0.w;
  PRECISE REAL y = ((row1.x * r.x + row1.y * r.y) + row1.z * r.z) + row1.w;
  PRECISE REAL z = ((row2.x * r.x + row2.y * r.y) + row2.z * r.z) + row2.w;
  PRECISE VEC3 out_sum = sum + VEC3(x, y, z) * w;
  return out_sum;
}

// The componentwise min and max (a box's corners, refitted).
SHARED_FN VEC3 min3(VEC3 a, VEC3 b) { return VEC3(min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)); }
SHARED_FN VEC3 max3(VEC3 a, VEC3 b) { return VEC3(max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)); }
// The box [lo, hi] widened to hold [a, b]; the first sets it (fit_collider_boxes' refits).
SHARED_FN void widen_box(INOUT(VEC3) lo, INOUT(VEC3) hi, VEC3 a, VEC3 b, bool first) {
  lo = first ? a : min3(lo, a);
  hi = first ? b : max3(hi, b);
}

// The squared distance from p to the box [lo, hi] (0 inside).
SHARED_FN REAL box_distance2(VEC3 p, VEC3 lo, VEC3 hi) {
  REAL dx = max(max(lo.x - p.x, p.x - hi.x), REAL(0));
  REAL dy = max(max(lo.y - p.y, p.y - hi.y), REAL(0));
  REAL dz = max(max(lo.z - p.z, p.z - hi.z), REAL(0));
  PRECISE REAL d2 = dx * dx + dy * dy + dz * dz;
  return d2;
}

// How far from x a skinned collider's triangle is looked for (docs/model.md, "Skinned and
// animated colliders"): the thickness, the mass's move d this substep and the surface's (at most
// `motion`, its vertices' largest move over the substep: the refit's), so that a mass further
// from every triangle can neither touch the surface nor cross it; plus one node spacing, since
// the trilinear field at a point is at most sqrt(3)/2 of a spacing below the distance there
// (each corner within its share of the cell's diagonal), and the frame's turn over the substep
// moves a point within reach by far less than the rest. A mass further than this is left
// alone, as it would be by the field of an unmoving body. `base` is the mass's own part
// (skinned_reach_base: once per mass), `motion` each super-group's.
SHARED_FN REAL skinned_reach_base(REAL thickness, VEC3 d) {
  PRECISE REAL base = thickness + length3(d);
  return base;
}
SHARED_FN REAL skinned_reach(REAL base, REAL motion, REAL inv_voxel) {
  PRECISE REAL reach = (base + motion) + REAL(1) / inv_voxel;
  return reach;
}

// A skinned collider's search keeps the least (squared distance, triangle index) of the triangles
// within their reach (each its super-group's: reach2, squared): the same triangle whatever order
// it visits them in, and whatever it starts from (the mass's nearest triangle of its last
// search, a cache). The best so far is at `best`, `found` (0xFFFFFFFFu for none yet).
SHARED_FN bool nearer(REAL d2, uint t, REAL reach2, REAL best, uint found) {
  if (!(d2 < reach2)) return false;
  return found == 0xFFFFFFFFu || d2 < best || (d2 == best && t < found);
}
// A box is passed over only when clearly further than the best so far (by 2^-10 of it): the
// rounding of a triangle's distance can never put it below its box's.
SHARED_FN bool box_beyond(REAL box_d2, REAL best) {
  PRECISE REAL slack = best * REAL(1.0009765625);
  return box_d2 > slack;
}

// The point of triangle (a, b, c) nearest p, and its barycentric coordinates (Ericson, Real-Time
// Collision Detection 5.1.5: the vertex regions, then the edges', then the face).
SHARED_FN VEC3 closest_on_triangle(VEC3 p, VEC3 a, VEC3 b, VEC3 c, OUT(VEC3) bary) {
  PRECISE VEC3 ab = b - a;
  PRECISE VEC3 ac = c - a;
  PRECISE VEC3 ap = p - a;
  REAL d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  bary = VEC3(REAL(1), REAL(0), REAL(0));
  if (d1 <= REAL(0) && d2 <= REAL(0)) return a;
  PRECISE VEC3 bp = p - b;
  REAL d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  bary = VEC3(REAL(0), REAL(1), REAL(0));
  if (d3 >= REAL(0) && d4 <= d3) return b;
  PRECISE REAL vc = d1 * d4 - d3 * d2;
  if (vc <= REAL(0) && d1 >= REAL(0) && d3 <= REAL(0)) {
    PRECISE REAL v = d1 / (d1 - d3);
    bary = VEC3(REAL(1) - v, v, REAL(0));
    PRECISE VEC3 on_ab = a + ab * v;
    return on_ab;
  }
  PRECISE VEC3 cp = p - c;
  REAL d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  bary = VEC3(REAL(0), REAL(0), REAL(1));
  if (d6 >= REAL(0) && d5 <= d6) return c;
  PRECISE REAL vb = d5 * d2 - d1 * d6;
  if (vb <= REAL(0) && d2 >= REAL(0) && d6 <= REAL(0)) {
    PRECISE REAL w = d2 / (d2 - d6);
    bary = VEC3(REAL(1) - w, REAL(0), w);
    PRECISE VEC3 on_ac = a + ac * w;
    return on_ac;
  }
  PRECISE REAL va = d3 * d6 - d5 * d4;
  PRECISE REAL e43 = d4 - d3;
  PRECISE REAL e56 = d5 - d6;
  if (va <= REAL(0) && e43 >= REAL(0) && e56 >= REAL(0)) {
    PRECISE REAL w = e43 / (e43 + e56);
    bary = VEC3(REAL(0), REAL(1) - w, w);
    PRECISE VEC3 on_bc = b + (c - b) * w;
    return on_bc;
  }
  PRECISE REAL denom = REAL(1) / ((va + vb) + vc);
  PRECISE REAL v = vb * denom;
  PRECISE REAL w = vc * denom;
  bary = VEC3((REAL(1) - v) - w, v, w);
  PRECISE VEC3 inside = (a + ab * v) + ac * w;
  return inside;
}

SHARED_FN VEC3 at_barycentric(VEC3 a, VEC3 b, VEC3 c, VEC3 bary) {
  PRECISE VEC3 p = (a * bary.x + b * bary.y) + c * bary.z;
  return p;
}

// Triangle (a, b, c)'s unit frame: u along ab, w its normal, v = w x u.
SHARED_FN void triangle_frame(VEC3 a, VEC3 b, VEC3 c, OUT(VEC3) u, OUT(VEC3) v, OUT(VEC3) w) {
  PRECISE VEC3 ab = b - a;
  PRECISE VEC3 ac = c - a;
  u = unit_or_up(ab);
  w = unit_or_up(cross3(ab, ac));
  v = cross3(w, u);
}

// The rows of R^T (to_local's rows), R the rotation that takes frame (u0, v0, w0) to (u, v, w):
// R = u u0^T + v v0^T + w w0^T, so row i of R^T is u0_i u + v0_i v + w0_i w.
SHARED_FN void frame_rows(VEC3 u0, VEC3 v0, VEC3 w0, VEC3 u, VEC3 v, VEC3 w, OUT(VEC3) r0, OUT(VEC3) r1, OUT(VEC3) r2) {
  PRECISE VEC3 a = (u * u0.x + v * v0.x) + w * w0.x;
  PRECISE VEC3 b = (u * u0.y + v * v0.y) + w * w0.y;
  PRECISE VEC3 c = (u * u0.z + v * v0.z) + w * w0.z;
  r0 = a;
  r1 = b;
  r2 = c;
}

// A mass at x that moved by d this substep, its nearest skinned triangle (a, b, c) now, (as, bs,
// cs) at the substep's start and (ar, br, cr) in the bind pose, its nearest point at `bary`:
// the mesh collider's frame for it, rows (to_local) and origin such that to_local(x - origin)
// puts x where its nearest point's bind-pose place is, rigidly; and the collider's motion m at
// the mass, chosen so that the response's path start p - to_local(d - m) is x - d carried into
// the bind pose by the start's frame (the surface's own motion under the mass, for friction).
SHARED_FN void skinned_frame(VEC3 a, VEC3 b, VEC3 c, VEC3 as, VEC3 bs, VEC3 cs, VEC3 ar, VEC3 br, VEC3 cr, VEC3 bary,
                             VEC3 x, VEC3 d, OUT(VEC3) r0, OUT(VEC3) r1, OUT(VEC3) r2, OUT(VEC3) origin,
                             OUT(VEC3) motion) {
  VEC3 u0, v0, w0, u, v, w, s0, s1, s2;
  triangle_frame(ar, br, cr, u0, v0, w0);
  triangle_frame(a, b, c, u, v, w);
  frame_rows(u0, v0, w0, u, v, w, r0, r1, r2);
  triangle_frame(as, bs, cs, u, v, w);
  frame_rows(u0, v0, w0, u, v, w, s0, s1, s2);
  VEC3 rest_point = at_barycentric(ar, br, cr, bary);
  PRECISE VEC3 o = at_barycentric(a, b, c, bary) - to_world(r0, r1, r2, rest_point);
  PRECISE VEC3 os = at_barycentric(as, bs, cs, bary) - to_world(s0, s1, s2, rest_point);
  origin = o;
  PRECISE VEC3 p = to_local(r0, r1, r2, x - o);
  PRECISE VEC3 p_start = to_local(s0, s1, s2, (x - d) - os);
  PRECISE VEC3 m = d - to_world(r0, r1, r2, p - p_start);
  motion = m;
}

SHARED_END

#endif

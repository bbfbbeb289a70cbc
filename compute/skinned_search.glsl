// A skinned mesh collider as a mass meets it (docs/model.md, "Skinned and animated colliders"):
// the search for the mass's nearest triangle, down the tree fit_collider_boxes refits, the frame
// of that triangle, and predict's test of whether the mass is near the body at all, with the far
// records that spare it (nearest.glsl). Included by collide_meshes.glsl after MeshField.
#ifndef CLOTHSIM_SKINNED_SEARCH_GLSL
#define CLOTHSIM_SKINNED_SEARCH_GLSL

#include "shared/skinning.glsl"
#include "skin_tree.glsl"
#include "nearest.glsl"

// A skinned collider's nearest triangle to a mass (skinned_mesh_at and mesh_at in
// host/core/reference/reference_skinning.hpp): the substep's first collision of the mass
// (g_search) looks for it, the least (distance, index) within reach, from the triangle its slot
// holds (found the same without it, only sooner), descending the groups and clusters whose boxes
// are not clearly further than the best so far or the reach, and keeps it in the slot; every
// later collision of the substep reuses the slot's (none: no contact). g_self < 0 (a pass that
// does not say whose collisions run): a search, kept nowhere. The reach is each super-group's
// (skinned_reach, with the largest move of its vertices that fit_collider_boxes left in its box).
int g_self = -1;         // the mass whose collisions run: set by the passes that know it
bool g_search = false;   // and whether this is its substep's first collision

// Mass `self`'s slot of skinned collider m in BINDING_NEAREST; skin_slot(m) is g_self's.
uint skin_slot_of(MeshField m, int self) { return uint(self) * params.skin_meshes + uint(m.skin.z); }
uint skin_slot(MeshField m) { return skin_slot_of(m, g_self); }
// A reach squared (skinned_reach) for a mass whose own part of it is `base`, from a super-group's
// or a root's box, whose lo.w is the largest move of the vertices under it.
float reach2_of(MeshField m, float base, vec4 lo) {
  float reach = skinned_reach(base, lo.w, m.inv_voxel);
  precise float reach2 = reach * reach;
  return reach2;
}
// Triangle t against the best so far, within reach2 (its super-group's reach, squared); returns
// its distance squared.
float visit_skinned_triangle(uint t, vec3 x, float reach2, inout float best, inout uint found) {
  uvec4 tri = texelFetch(skin_indices_view, int(params.skin_vertices + t));
  vec3 b3;
  vec3 q = closest_on_triangle(x, texelFetch(skinned_view, int(tri.x)).xyz, texelFetch(skinned_view, int(tri.y)).xyz,
                               texelFetch(skinned_view, int(tri.z)).xyz, b3);
  float d2 = dot3(x - q, x - q);
  if (nearer(d2, t, reach2, best, found)) {
    best = d2;
    found = t;
  }
  return d2;
}
// A walk of the tree (roots, super-groups, groups, clusters, triangles: levels 0 to 4) for a mass
// at x whose own part of the reach is `base`, one box or one triangle per trip of a single loop,
// each lane at its own place in the tree. Why one loop: llvmpipe runs 8 masses in lockstep, and
// nested loops cost the union of the boxes the 8 open (a lane waits out a group its neighbour
// opened), where one loop costs the most that any one of them visits. A box clearly further than
// the best so far or the reach is passed over; until a triangle is found, the reach widened by
// `wider`, so that a search that finds none leaves a bound worth keeping: low2, at most the
// distance squared of every triangle (the least of those it visits and of the boxes it passes
// over). With `to_triangles` it is the search (the least triangle
// into best and found; the order does not change it: nearer); without, predict's test, which
// stops at the first group within reach and returns true.
bool walk_skinned_tree(MeshField m, vec3 x, float base, float wider, bool to_triangles, inout float best,
                       inout uint found, inout float low2) {
  SkinTree tree = skin_tree();
  uint first = uint(m.skin.x), last = uint(m.skin.x + m.skin.y), size = uint(WORKGROUP_SIZE);
  float reach2 = 0.0, wide2 = 0.0;
  // The cursor: at_l the box (or triangle) level l is at, end_l where its run ends.
  uint at0 = first / size, end0 = (last - 1u) / size + 1u, at1 = 0u, end1 = 0u, at2 = 0u, end2 = 0u;
  uint at3 = 0u, end3 = 0u, at4 = 0u, end4 = 0u;
  int level = 0;
  for (;;) {
    // Up from the runs that are done, to the next box of the level above.
    if (level == 4 && at4 >= end4) { level = 3; ++at3; }
    if (level == 3 && at3 >= end3) { level = 2; ++at2; }
    if (level == 2 && at2 >= end2) { level = 1; ++at1; }
    if (level == 1 && at1 >= end1) { level = 0; ++at0; }
    if (level == 0 && at0 >= end0) return false;
    if (level == 4) {
      low2 = min(low2, visit_skinned_triangle(at4, x, reach2, best, found));
      ++at4;
      continue;
    }
    uint i = level == 0 ? at0 : level == 1 ? at1 : level == 2 ? at2 : at3;
    uint box = (level == 0 ? tree.root_boxes : level == 1 ? tree.super_boxes : level == 2 ? tree.group_boxes : tree.boxes) + 2u * i;
    vec4 lo = texelFetch(skinned_view, int(box));
    if (level <= 1) {  // a super-group's reach holds under it
      float reach = skinned_reach(base, lo.w, m.inv_voxel);
      precise float r2 = reach * reach, w = reach + wider, w2 = w * w;
      reach2 = r2;
      wide2 = w2;
    }
    float bound = found == 0xFFFFFFFFu ? wide2 : min(best, reach2);
    float box_d2 = box_distance2(x, lo.xyz, texelFetch(skinned_view, int(box) + 1).xyz);
    bool beyond = box_beyond(box_d2, bound);
    // predict's test: a group within reach lists the mass; one only within the wider bound is passed over.
    if (!to_triangles && !beyond && level == 2) {
      if (!box_beyond(box_d2, reach2)) return true;
      beyond = true;
    }
    if (beyond) low2 = min(low2, box_d2 * (1.0 - 1.0 / 512.0));  // its triangles' distances round to no less
    uvec2 run = uvec2(max(first, i * size), min(last, (i + 1u) * size));  // a root's super-groups
    if (!beyond && level > 0) {
      uvec4 list = texelFetch(skin_indices_view, int((level == 1 ? tree.supers_at : level == 2 ? tree.groups_at : tree.clusters_at) + i));
      run = uvec2(list.x, list.x + list.y);
    }
    if (beyond) {
      if (level == 0) ++at0; else if (level == 1) ++at1; else if (level == 2) ++at2; else ++at3;
    } else if (level == 0) { at1 = run.x; end1 = run.y; level = 1; }
    else if (level == 1) { at2 = run.x; end2 = run.y; level = 2; }
    else if (level == 2) { at3 = run.x; end3 = run.y; level = 3; }
    else { at4 = run.x; end4 = run.y; level = 4; }
  }
}
// Mass g_self's far record (nearest.glsl): where it is, and low2, at most the distance squared of
// every triangle (0: no record), less a margin for its rounding, plus the summed moves.
void keep_far_record(MeshField m, vec3 x, float low2) {
  uint at = far_record_at(skin_slot(m));
  precise float keep = sqrt(low2) * (1.0 - 1.0 / 512.0) + skin_moved();
  nearest[at] = floatBitsToUint(x.x);
  nearest[at + 1u] = floatBitsToUint(x.y);
  nearest[at + 2u] = floatBitsToUint(x.z);
  nearest[at + 3u] = floatBitsToUint(low2 > 0.0 ? keep : 0.0);
}
uint search_skinned_triangle(MeshField m, vec3 x, vec3 d) {
  float base = skinned_reach_base(m.thickness, d), best = 0.0, low2 = 3.0e38;  // (best: none found yet, the reach bounds alone)
  uint found = 0xFFFFFFFFu;
  if (g_self >= 0 && nearest[skin_slot(m)] != 0xFFFFFFFFu) {
    uint t = nearest[skin_slot(m)];  // w of its texel: its super-group
    uint s = texelFetch(skin_indices_view, int(params.skin_vertices + t)).w;
    low2 = visit_skinned_triangle(t, x, reach2_of(m, base, texelFetch(skinned_view, int(skin_tree().super_boxes + 2u * s))), best, found);
  }
  walk_skinned_tree(m, x, base, SKIN_FAR_MARGIN / m.inv_voxel, true, best, found, low2);
  if (g_self < 0) return found;
  nearest[skin_slot(m)] = found;
  keep_far_record(m, x, found == 0xFFFFFFFFu ? low2 : 0.0);
  return found;
}

// Mesh collider m as it meets a mass at x that moved by d: a skinned one takes the frame of its
// nearest triangle (skinned_frame); false where it has none (nothing to collide with).
bool mesh_at(inout MeshField m, vec3 x, vec3 d) {
  if (!SKINNED_MESHES || m.skin.y == 0) return true;
  uint t = g_self < 0 || g_search ? search_skinned_triangle(m, x, d) : nearest[skin_slot(m)];
  if (t == 0xFFFFFFFFu) return false;
  uint n = params.skin_vertices;
  uvec4 tri = texelFetch(skin_indices_view, int(n + t));
  vec3 a = texelFetch(skinned_view, int(tri.x)).xyz, b = texelFetch(skinned_view, int(tri.y)).xyz;
  vec3 c = texelFetch(skinned_view, int(tri.z)).xyz, bary, origin, motion;
  closest_on_triangle(x, a, b, c, bary);
  skinned_frame(a, b, c, texelFetch(skinned_view, int(n + tri.x)).xyz, texelFetch(skinned_view, int(n + tri.y)).xyz,
                texelFetch(skinned_view, int(n + tri.z)).xyz, texelFetch(skinned_view, int(2u * n + tri.x)).xyz,
                texelFetch(skinned_view, int(2u * n + tri.y)).xyz, texelFetch(skinned_view, int(2u * n + tri.z)).xyz, bary,
                x, d, m.rows[0], m.rows[1], m.rows[2], origin, motion);
  m.origin = origin;
  m.motion = motion;
  return true;
}

// Whether mass g_self's far record (nearest.glsl) still keeps every triangle of m beyond its reach
// (the largest of this substep's, with every vertex's move: skin_motion): the record's bound
// less the surface's moves since and the mass's own, with a margin for their rounding.
bool far_from_skin(MeshField m, vec3 x, float base) {
  uint at = far_record_at(skin_slot(m));
  vec4 record = uintBitsToFloat(uvec4(nearest[at], nearest[at + 1u], nearest[at + 2u], nearest[at + 3u]));
  float moved = skin_moved();
  precise float room = (record.w - moved) - length3(x - record.xyz);
  precise float reach = skinned_reach(base, skin_motion(), m.inv_voxel), needed = (reach * (1.0 + 1.0 / 512.0) + 1e-5) + moved * 1e-6;
  return room > needed;
}
// Whether a skinned collider leaves a mass at x, moved by d, alone at the substep's first
// collision: its far record holds, or no group's box is within its super-group's reach (a
// super-group's box beyond it holds none), where the search finds no triangle. The mass is then
// not listed, so its slot is cleared here, as that search would have, and its record kept.
bool skinned_leaves_alone(MeshField m, vec3 x, vec3 d) {
  float best = 0.0, low2 = 3.0e38, base = skinned_reach_base(m.thickness, d);
  uint found = 0xFFFFFFFFu;
  // A record that holds was kept by a walk or search that found none, and the slot has held none
  // since (a search that finds one voids the record; a state loaded voids them all): no write.
  if (g_self >= 0 && far_from_skin(m, x, base)) return true;
  if (walk_skinned_tree(m, x, base, SKIN_FAR_MARGIN / m.inv_voxel, false, best, found, low2)) return false;
  if (g_self >= 0) {
    nearest[skin_slot(m)] = 0xFFFFFFFFu;
    keep_far_record(m, x, low2);
  }
  return true;
}

#endif

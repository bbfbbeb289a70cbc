// Mesh colliders (docs/model.md, "Mesh colliders"): a mass against a mesh's signed distance
// field. The formulas are compute/shared/mesh_field.glsl's; this file reads the field's
// parameters and nodes and walks a path. Included by collide_objects.glsl after the contact
// response it shares (respond_to_contact).
#ifndef CLOTHSIM_COLLIDE_MESHES_GLSL
#define CLOTHSIM_COLLIDE_MESHES_GLSL

#include "particle_views.glsl"
#include "shared/mesh_field.glsl"
#include "shared/skinning.glsl"
#include "skin_tree.glsl"

struct MeshField {
  vec3 rows[3];
  vec3 origin, motion;
  float keep, mu, thickness, crossing;
  bool closed;
  vec3 grid_min;
  float inv_voxel;
  ivec4 dims;  // w: the offset of node (0, 0, 0) in sdf_view
  float slope;  // the sampled field's Lipschitz bound in the world (mesh_leaves_alone_after)
  ivec4 skin;   // a skinned collider: x its first super-group, y its super-groups (0: rigid)
};

MeshField mesh_field(int k) {
  vec4 r0 = texelFetch(meshes_view, MESH_TEXELS * k), r1 = texelFetch(meshes_view, MESH_TEXELS * k + 1);
  vec4 r2 = texelFetch(meshes_view, MESH_TEXELS * k + 2), grid = texelFetch(meshes_view, MESH_TEXELS * k + 3);
  ivec4 dims = texelFetch(meshes_int_view, MESH_TEXELS * k + 4);  // integers: through the integer view
  vec4 motion = texelFetch(meshes_view, MESH_TEXELS * k + 5), material = texelFetch(meshes_view, MESH_TEXELS * k + 6);
  vec4 bound = texelFetch(meshes_view, MESH_TEXELS * k + 7);
  MeshField m;
  m.rows[0] = r0.xyz;
  m.rows[1] = r1.xyz;
  m.rows[2] = r2.xyz;
  m.origin = vec3(r0.w, r1.w, r2.w);
  m.motion = collider_motion(motion.xyz);
  m.keep = motion.w;
  m.mu = material.x;
  m.thickness = material.y;
  m.crossing = material.z;
  m.closed = material.w != 0.0;
  m.grid_min = grid.xyz;
  m.inv_voxel = grid.w;
  m.dims = dims;
  m.slope = bound.x;
  m.skin = texelFetch(meshes_int_view, MESH_TEXELS * k + 8);
  return m;
}

// A skinned collider's nearest triangle to a mass (skinned_mesh_at and mesh_at in
// host/core/reference/reference_skinning.hpp): the substep's first collision of the mass
// (g_search) looks for it, the least (distance, index) within reach, from the triangle its slot
// holds (found the same without it, only sooner), descending the groups and clusters whose boxes
// are not clearly further than the best so far or the reach, and keeps it in the slot; every
// later collision of the substep reuses the slot's (none: no contact). g_self < 0 (a pass that
// does not say whose collisions run): a search, kept nowhere. The reach is each super-group's
// (skinned_reach, with the largest move of its vertices that fit_collider_boxes left in its box).
layout(std430, binding = BINDING_NEAREST) buffer Nearest { uint nearest[]; };
int g_self = -1;         // the mass whose collisions run: set by the passes that know it
bool g_search = false;   // and whether this is its substep's first collision

// Mass `self`'s slot of skinned collider m in BINDING_NEAREST; skin_slot(m) is g_self's.
uint skin_slot_of(MeshField m, int self) { return uint(self) * params.skin_meshes + uint(m.skin.z); }
uint skin_slot(MeshField m) { return skin_slot_of(m, g_self); }
bool skinned_beyond(uint box, vec3 x, float best) {
  return box_beyond(box_distance2(x, texelFetch(skinned_view, int(box)).xyz, texelFetch(skinned_view, int(box) + 1).xyz), best);
}
// A reach squared (skinned_reach) for a mass whose own part of it is `base`, from a super-group's
// or a root's box, whose lo.w is the largest move of the vertices under it.
float reach2_of(MeshField m, float base, vec4 lo) {
  float reach = skinned_reach(base, lo.w, m.inv_voxel);
  precise float reach2 = reach * reach;
  return reach2;
}
// What a box is passed over beyond: the reach, or the best so far once one is found.
float search_bound(uint found, float best, float reach2) { return found == 0xFFFFFFFFu ? reach2 : min(best, reach2); }
// Whether the super-group's or root's box at `box` is clearly further from x than search_bound,
// with its reach squared in reach2 (for what lies under it).
bool reach_box_beyond(MeshField m, uint box, vec3 x, float base, uint found, float best, out float reach2) {
  vec4 lo = texelFetch(skinned_view, int(box));
  reach2 = reach2_of(m, base, lo);
  return box_beyond(box_distance2(x, lo.xyz, texelFetch(skinned_view, int(box) + 1).xyz), search_bound(found, best, reach2));
}
// Triangle t against the best so far, within reach2 (its super-group's reach, squared).
void visit_skinned_triangle(uint t, vec3 x, float reach2, inout float best, inout uint found) {
  uvec4 tri = texelFetch(skin_indices_view, int(params.skin_vertices + t));
  vec3 b3;
  vec3 q = closest_on_triangle(x, texelFetch(skinned_view, int(tri.x)).xyz, texelFetch(skinned_view, int(tri.y)).xyz,
                               texelFetch(skinned_view, int(tri.z)).xyz, b3);
  float d2 = dot3(x - q, x - q);
  if (nearer(d2, t, reach2, best, found)) {
    best = d2;
    found = t;
  }
}
// Super-group s's groups, clusters and triangles for the search (a box clearly further than the
// best so far or the reach passed over).
void search_super_group(MeshField m, SkinTree tree, uint s, vec3 x, float base, inout float best, inout uint found) {
  float reach2;
  if (reach_box_beyond(m, tree.super_boxes + 2u * s, x, base, found, best, reach2)) return;
  uvec4 super_group = texelFetch(skin_indices_view, int(tree.supers_at + s));
  for (uint g = super_group.x; g < super_group.x + super_group.y; ++g) {
    if (skinned_beyond(tree.group_boxes + 2u * g, x, search_bound(found, best, reach2))) continue;
    uvec4 group = texelFetch(skin_indices_view, int(tree.groups_at + g));
    for (uint k = group.x; k < group.x + group.y; ++k) {
      if (skinned_beyond(tree.boxes + 2u * k, x, search_bound(found, best, reach2))) continue;
      uvec4 cluster = texelFetch(skin_indices_view, int(tree.clusters_at + k));
      for (uint t = cluster.x; t < cluster.x + cluster.y; ++t) visit_skinned_triangle(t, x, reach2, best, found);
    }
  }
}
uint search_skinned_triangle(MeshField m, vec3 x, vec3 d) {
  SkinTree tree = skin_tree();
  float base = skinned_reach_base(m.thickness, d), best = 0.0, reach2;  // (best: none found yet, the reach bounds alone)
  uint found = 0xFFFFFFFFu;
  if (g_self >= 0 && nearest[skin_slot(m)] != 0xFFFFFFFFu) {
    uint t = nearest[skin_slot(m)];  // w of its texel: its super-group
    uint s = texelFetch(skin_indices_view, int(params.skin_vertices + t)).w;
    visit_skinned_triangle(t, x, reach2_of(m, base, texelFetch(skinned_view, int(tree.super_boxes + 2u * s))), best, found);
  }
  uint first = uint(m.skin.x), last = uint(m.skin.x + m.skin.y), size = uint(WORKGROUP_SIZE);
  for (uint r = first / size; r <= (last - 1u) / size; ++r) {
    if (reach_box_beyond(m, tree.root_boxes + 2u * r, x, base, found, best, reach2)) continue;
    for (uint s = max(first, r * size); s < min(last, (r + 1u) * size); ++s)
      search_super_group(m, tree, s, x, base, best, found);
  }
  if (g_self >= 0) nearest[skin_slot(m)] = found;
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

// Whether a skinned collider leaves a mass at x, moved by d, alone at the substep's first
// collision: no group's box within its super-group's reach (a super-group's box beyond it holds
// none), where the search finds no triangle. The mass is then not listed, so its slot is
// cleared here, as that search would have.
bool skinned_leaves_alone(MeshField m, vec3 x, vec3 d) {
  SkinTree tree = skin_tree();
  float base = skinned_reach_base(m.thickness, d);
  uint first = uint(m.skin.x), last = uint(m.skin.x + m.skin.y), size = uint(WORKGROUP_SIZE);
  float reach2;
  for (uint r = first / size; r <= (last - 1u) / size; ++r) {
    if (reach_box_beyond(m, tree.root_boxes + 2u * r, x, base, 0xFFFFFFFFu, 0.0, reach2)) continue;
    for (uint s = max(first, r * size); s < min(last, (r + 1u) * size); ++s) {
      if (reach_box_beyond(m, tree.super_boxes + 2u * s, x, base, 0xFFFFFFFFu, 0.0, reach2)) continue;
      uvec4 super_group = texelFetch(skin_indices_view, int(tree.supers_at + s));
      for (uint g = super_group.x; g < super_group.x + super_group.y; ++g)
        if (!skinned_beyond(tree.group_boxes + 2u * g, x, reach2)) return false;
    }
  }
  if (g_self >= 0) nearest[skin_slot(m)] = 0xFFFFFFFFu;
  return true;
}

vec3 mesh_local(MeshField m, vec3 v) { return to_local(m.rows[0], m.rows[1], m.rows[2], v); }

// Whether local point p is inside the field's grid, and its grid coordinates g.
bool inside_mesh_grid(MeshField m, vec3 p, out vec3 g) {
  return inside_grid(p, m.grid_min, m.inv_voxel, vec3(m.dims.xyz - 1), g);
}

// The field at local point p, and whether p is inside the grid. Outside, the value at the
// grid's point nearest p: the field extended outward unchanged along each face's normal, as
// Lipschitz as the field inside (the nearest point of a box moves no farther than p does),
// which the contact list's bound needs (mesh_leaves_alone_after). Inside, the clamps change
// nothing, so the value is the same bits as sample_mesh_field's.
bool sample_mesh_field_clamped(MeshField m, vec3 p, out float phi, out vec3 grad) {
  vec3 g;
  bool inside = inside_mesh_grid(m, p, g);
  vec3 top = vec3(m.dims.xyz - 1);
  vec3 nearest = clamp(g, vec3(0.0), top);
  vec3 cell = min(floor(nearest), top - 1.0);
  precise vec3 f = nearest - cell;
  int nx = m.dims.x, nxy = m.dims.x * m.dims.y;
  int base = m.dims.w + int(cell.x) + nx * int(cell.y) + nxy * int(cell.z);
  // A texel holds a node and its +x, +y and +x+y neighbours (host/gpu/sdf_texels.hpp): the
  // cell's lower and upper faces, two fetches for the eight corners.
  vec4 lower = texelFetch(sdf_view, base), upper = texelFetch(sdf_view, base + nxy);
  float c000 = lower.x, c100 = lower.y, c010 = lower.z, c110 = lower.w;
  float c001 = upper.x, c101 = upper.y, c011 = upper.z, c111 = upper.w;
  phi = trilinear(c000, c100, c010, c110, c001, c101, c011, c111, f, grad);
  return inside;
}

// The field at local point p: false outside the grid.
bool sample_mesh_field(MeshField m, vec3 p, out float phi, out vec3 grad) {
  bool inside = sample_mesh_field_clamped(m, p, phi, grad);
  if (!inside) {
    phi = 0.0;
    grad = vec3(0.0);
  }
  return inside;
}

// The outward unit normal in the world; false where the field is flat.
bool mesh_normal(MeshField m, vec3 grad, out vec3 n) { return world_normal(m.rows[0], m.rows[1], m.rows[2], grad, n); }

// A mass outside the offset surface that moved by rel further than its clearance: true if its
// path (sampled every half node spacing, at most 8 samples) went through a closed mesh's wall
// or an open mesh's wall, hole or shell, with t - x the way back to the sample before (passed_through_mesh
// in host/core/reference/reference_mesh_collisions.cpp says how).
bool passed_through_mesh(MeshField m, vec3 p, float phi, vec3 rel, out vec3 t_minus_x) {
  t_minus_x = vec3(0.0);
  float moved = length3(rel);
  if (stays_clear_of_mesh(moved, phi, m.thickness)) return false;
  vec3 step_all = mesh_local(m, rel);
  int samples = path_samples(moved, m.inv_voxel);
  precise float spacing = moved * (1.0 / float(samples));
  precise vec3 start = p - step_all;
  float prev_phi = 0.0, prev_slope = 0.0;
  bool prev_in_grid = false;
  // A closed mesh's ends are not sampled (the path starts and ends outside it): the loop leaves
  // them out rather than skipping them, since llvmpipe runs a loop's body as often as its longest
  // lane, skipped or not. The same samples in the same order as the reference.
  int first = m.closed ? 1 : 0, last = m.closed ? samples - 1 : samples;
  for (int k = first; k <= last; ++k) {
    precise vec3 q = start + step_all * (float(k) / float(samples));
    float phi_q;
    vec3 grad;
    bool in_grid = sample_mesh_field(m, q, phi_q, grad);
    bool crossed = false;
    if (m.closed) {
      crossed = in_grid && phi_q < 0.0;
    } else if (in_grid) {
      float slope = dot3(grad, step_all);
      crossed = crossed_open_mesh(k, prev_in_grid, prev_slope, slope, prev_phi, phi_q, spacing, m.crossing);
      prev_phi = phi_q;
      prev_slope = slope;
    }
    prev_in_grid = in_grid;
    if (!crossed) continue;
    precise vec3 back = start + step_all * (float(k - 1) / float(samples));
    t_minus_x = to_world(m.rows[0], m.rows[1], m.rows[2], back - p);
    return true;
  }
  return false;
}

// A mass deeper than 0.1 mm inside the offset surface goes out along the gradient, without
// friction.
void keep_out_of_mesh(MeshField m, inout vec3 x, inout vec3 d) {
  vec3 p = mesh_local(m, x - m.origin);
  float phi;
  vec3 grad, n;
  if (!sample_mesh_field(m, p, phi, grad)) return;
  precise float depth = m.thickness - phi;
  if (!(depth > 1e-4) || !mesh_normal(m, grad, n)) return;
  push_out_of_mesh(n, depth, x, d);
}

// Whether collide_with_mesh leaves a mass at x, moved by d, unchanged at its first tests: outside
// the field's grid, or outside the offset surface with a path too short to have reached it.
// The same functions on the same values as collide_with_mesh and passed_through_mesh, so the
// contact list's decision (may_collide) is the one the full response makes. `clearance` takes
// the min with this mesh's bound for mesh_leaves_alone_after (predict's is kept).
bool mesh_leaves_alone(MeshField m, vec3 x, vec3 d, inout float clearance) {
  if (SKINNED_MESHES && m.skin.y > 0) return skinned_leaves_alone(m, x, d);  // `clearance` bounds the rigid ones alone
  vec3 p = mesh_local(m, x - m.origin);
  float phi;
  vec3 grad;
  bool inside = sample_mesh_field_clamped(m, p, phi, grad);
  // At s = x - d, where the mass started the substep, the (extended) field is at least
  // phi - slope |d|: the clearance bound the passes after this one start from.
  precise float below = (phi - m.slope * length3(d)) - m.thickness;
  clearance = min(clearance, below);
  if (!inside) return true;
  return !(phi < m.thickness) && stays_clear_of_mesh(length3(d - m.motion), phi, m.thickness);
}

// The same decision in the passes after predict (xpbd's and multigrid's sweeps) without a
// field sample: a mass that predict found `clearance` outside every mesh's offset surface at
// the substep's start s = x - d (the bound above, kept in its displacement's w) is still at
// least clearance - slope |d| outside at x, the field being slope-Lipschitz along the way
// (inside the grid the trilinear interpolant of nodes whose neighbours differ by at most D per
// axis has a gradient of at most |D| / spacing: host/gpu/sdf_texels.hpp, sdf_slopes). Where
// that exceeds the way it moved relative to the mesh, with a margin for the rounding of every
// step (the samples, the frame change, x - d drifting by an ulp per correction), the response
// would stop at its first tests: left alone. Otherwise listed, and the listed response samples
// and decides: a listed mass it leaves alone costs time, never bits. A clearance of 0 (a pass
// that does not keep it, a pinned mass) lists every mass inside the grid.
bool mesh_leaves_alone_after(MeshField m, vec3 x, vec3 d, float clearance, int self) {
  // A skinned one: its later collisions reuse the slot, and do nothing where it holds none.
  if (SKINNED_MESHES && m.skin.y > 0) return nearest[skin_slot_of(m, self)] == 0xFFFFFFFFu;
  vec3 p = mesh_local(m, x - m.origin), g;
  if (!inside_mesh_grid(m, p, g)) return true;
  precise float scale = ((length3(x) + length3(m.origin)) + length3(m.grid_min)) + (abs(clearance) + 0.01);
  precise float margin = 1e-4 * (1.0 + m.slope) * scale;
  precise float room = (clearance - m.slope * length3(d)) - margin;
  return room > length3(d - m.motion);
}

// One mesh collider.
void collide_with_mesh(int k, bool friction, inout vec3 x, inout vec3 d) {
  MeshField m = mesh_field(k);
  if (!mesh_at(m, x, d)) return;
  vec3 p = mesh_local(m, x - m.origin);
  float phi;
  vec3 grad, n;
  precise vec3 t_minus_x;
  if (!sample_mesh_field(m, p, phi, grad)) return;
  if (phi < m.thickness) {
    if (!mesh_normal(m, grad, n)) return;
    precise float depth = m.thickness - phi;
    t_minus_x = n * depth;
  } else {
    vec3 back;
    if (!passed_through_mesh(m, p, phi, d - m.motion, back)) return;
    t_minus_x = back;
    float phi_back;
    vec3 grad_back;
    if (!sample_mesh_field(m, p + mesh_local(m, t_minus_x), phi_back, grad_back) || !mesh_normal(m, grad_back, n)) {
      precise vec3 along = t_minus_x * (1.0 / length3(t_minus_x));
      n = along;
    }
  }
  respond_to_contact(friction && COULOMB_FRICTION, t_minus_x, n, friction ? m.keep : 1.0, m.mu, m.motion,
                     x, d);
  keep_out_of_mesh(m, x, d);
}

#endif

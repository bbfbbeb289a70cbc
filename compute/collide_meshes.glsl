// Mesh colliders (docs/model.md, "Mesh colliders"): a mass against a mesh's signed distance
// field. The formulas are compute/shared/mesh_field.glsl's; this file reads the field's
// parameters and nodes and walks a path. Included by collide_objects.glsl after the contact
// response it shares (respond_to_contact).
#ifndef CLOTHSIM_COLLIDE_MESHES_GLSL
#define CLOTHSIM_COLLIDE_MESHES_GLSL

#include "particle_views.glsl"
#include "shared/mesh_field.glsl"

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

#include "skinned_search.glsl"  // mesh_at, skinned_leaves_alone: a skinned collider through its nearest triangle

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
  bool held = takes_friction(friction, g_friction_still_only, m.motion);
  respond_to_contact(held && COULOMB_FRICTION, t_minus_x, n, held ? m.keep : 1.0, m.mu, m.motion, x, d);
  keep_out_of_mesh(m, x, d);
}

#endif

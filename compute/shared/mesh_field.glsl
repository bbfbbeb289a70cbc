// A mesh collider's signed distance field (docs/model.md, "Mesh colliders"): the frame change,
// the grid test, the trilinear interpolation written out (no sampler filtering) and the pushes
// built on them. Included by compute/collide_meshes.glsl and
// host/core/reference/reference_mesh_collisions.cpp; reading the eight nodes of a cell, and the
// walk along a path, stay with each backend.
#ifndef CLOTHSIM_SHARED_MESH_FIELD_GLSL
#define CLOTHSIM_SHARED_MESH_FIELD_GLSL

#include "vector.glsl"

SHARED_BEGIN

// Local = rows (v) and world = rows^T (v), rows r0, r1, r2 the rotation's transpose.
SHARED_FN VEC3 to_local(VEC3 r0, VEC3 r1, VEC3 r2, VEC3 v) { return VEC3(dot3(r0, v), dot3(r1, v), dot3(r2, v)); }
SHARED_FN VEC3 to_world(VEC3 r0, VEC3 r1, VEC3 r2, VEC3 v) {
  PRECISE VEC3 w = (r0 * v.x + r1 * v.y) + r2 * v.z;
  return w;
}

// The grid coordinates of local point p, and whether they are inside the grid of top + 1 nodes
// per axis (outside, the mesh is further than its band: no contact, and no read out of it).
SHARED_FN bool inside_grid(VEC3 p, VEC3 grid_min, REAL inv_voxel, VEC3 top, OUT(VEC3) g) {
  PRECISE VEC3 at = (p - grid_min) * inv_voxel;
  g = at;
  return at.x >= REAL(0) && at.y >= REAL(0) && at.z >= REAL(0) && at.x < top.x && at.y < top.y && at.z < top.z;
}

// The trilinear interpolation of a cell's corners c_xyz at fractions f, along x, then y, then z;
// the gradient is the trilinear's own (per cell, up to 1 / voxel, which the normalisation drops).
SHARED_FN REAL trilinear(REAL c000, REAL c100, REAL c010, REAL c110, REAL c001, REAL c101, REAL c011, REAL c111, VEC3 f,
                         OUT(VEC3) grad) {
  PRECISE REAL x00 = c100 - c000;
  PRECISE REAL x10 = c110 - c010;
  PRECISE REAL x01 = c101 - c001;
  PRECISE REAL x11 = c111 - c011;
  PRECISE REAL c00 = c000 + x00 * f.x;
  PRECISE REAL c10 = c010 + x10 * f.x;
  PRECISE REAL c01 = c001 + x01 * f.x;
  PRECISE REAL c11 = c011 + x11 * f.x;
  PRECISE REAL y0 = c10 - c00;
  PRECISE REAL y1 = c11 - c01;
  PRECISE REAL c0 = c00 + y0 * f.y;
  PRECISE REAL c1 = c01 + y1 * f.y;
  PRECISE REAL z = c1 - c0;
  PRECISE REAL value = c0 + z * f.z;
  PRECISE REAL gx0 = x00 + (x10 - x00) * f.y;
  PRECISE REAL gx1 = x01 + (x11 - x01) * f.y;
  PRECISE VEC3 gradient = VEC3(gx0 + (gx1 - gx0) * f.z, y0 + (y1 - y0) * f.z, z);
  grad = gradient;
  return value;
}

// The outward unit normal in the world for a field gradient; false where the field is flat
// (beyond the band on both sides of a cell: no direction to push along).
SHARED_FN bool world_normal(VEC3 r0, VEC3 r1, VEC3 r2, VEC3 grad, OUT(VEC3) n) {
  n = VEC3(REAL(0));
  REAL len = length3(grad);
  if (!(len > REAL(0))) return false;
  PRECISE VEC3 unit = grad * (REAL(1) / len);
  n = to_world(r0, r1, r2, unit);
  return true;
}

// A mass phi from the surface, thickness its offset, that moved `moved` relative to the mesh:
// true if it cannot have reached the offset surface (passed_through_mesh's first test, and
// may_collide's on the same values).
SHARED_FN bool stays_clear_of_mesh(REAL moved, REAL phi, REAL thickness) {
  PRECISE REAL clearance = phi - thickness;
  return !(moved > clearance);
}

// The samples of a path of length `moved` through the field: one every half node spacing, at
// most 8.
SHARED_FN int path_samples(REAL moved, REAL inv_voxel) {
  PRECISE REAL halves = ceil(moved * inv_voxel * REAL(2));
  return int(min(REAL(8), halves));
}

// Sample k of an open mesh's path crossed it. Its field is signed by the winding number
// (colliders/sdf.hpp): a sample past its zero level set (inside one of its closed parts, or past
// the level set that closes a hole) crossed as in a closed mesh; the path's start is not tested
// (it may begin inside, where the last substep left it). Where the field stays unsigned (a thin
// open sheet), its shell lies between two neighbouring samples, the first approaching the
// surface and the second leaving it (the field's slope along the path from < 0 to > 0), whose
// distances add up to less than their spacing plus twice `crossing`.
SHARED_FN bool crossed_open_mesh(int k, bool prev_in_grid, REAL prev_slope, REAL slope, REAL prev_phi, REAL phi,
                                 REAL spacing, REAL crossing) {
  PRECISE REAL both = prev_phi + phi;
  PRECISE REAL reach = spacing + REAL(2) * crossing;
  bool inside = k > 0 && phi < REAL(0);
  return inside || (prev_in_grid && prev_slope < REAL(0) && slope > REAL(0) && both < reach);
}

// A mass `depth` (> 0.1 mm) inside the offset surface goes out along the normal n, without friction.
SHARED_FN void push_out_of_mesh(VEC3 n, REAL depth, INOUT(VEC3) x, INOUT(VEC3) d) {
  PRECISE VEC3 out_along_n = n * depth;
  PRECISE VEC3 nx = x + out_along_n;
  PRECISE VEC3 nd = d + out_along_n;
  x = nx;
  d = nd;
}

SHARED_END

#endif

// The springs' formulas: a spring's force on its end, Provot's stretch limit, xpbd's distance
// constraint, and the multigrid solver's Newton terms (a spring's Hessian, a symmetric 3x3
// block and its solve). Included by compute/forces.glsl, compute/constraint_colour.glsl,
// compute/multigrid.glsl, the passes that use them, and by host/core/reference
// (reference_forces.cpp, reference_constraints.cpp, reference_multigrid.cpp); the gathers over a
// particle's springs and the reads of their ends stay with each backend.
#ifndef CLOTHSIM_SHARED_SPRINGS_GLSL
#define CLOTHSIM_SHARED_SPRINGS_GLSL

#include "vector.glsl"

// A symmetric 3x3 matrix: a = (xx, xy, xz), b = (yy, yz, zz).
#ifdef __cplusplus
SHARED_BEGIN
template <class REAL> struct Sym3 {
  VEC3 a;
  VEC3 b;
};
SHARED_END
#define SYM3 Sym3<REAL>
#else
struct Sym3 {
  vec3 a;
  vec3 b;
};
#define SYM3 Sym3
#endif

SHARED_BEGIN

// f plus the force of a spring of stiffness k and rest length `rest` along e (from the particle
// to its other end): k (|e| - rest) e / |e|. Coincident ends add nothing. Divisions are written
// as x * (1 / y), as the GLSL compiler lowers a / b.
SHARED_FN VEC3 add_spring_force(VEC3 f, VEC3 e, REAL rest, REAL k) {
  REAL len = length3(e);
  if (!(len > REAL(0))) return f;
  PRECISE REAL inv = REAL(1) / len;
  PRECISE REAL magnitude = k * (len - rest) * inv;
  PRECISE VEC3 sum = f + e * magnitude;
  return sum;
}

// A seam's rest length now (docs/model.md, "Sewing"): the pair's start distance less what the
// seams have shrunk by (sewing_speed x time), never below zero: a zero-length spring once sewn.
SHARED_FN REAL seam_rest(REAL start, REAL shrunk) { return max(REAL(0), start - shrunk); }

// f plus the pull of an attachment (docs/model.md, "Attachments"): a zero-length spring of
// stiffness k from x to its anchor, `rel` (the start position less the collider's start origin)
// plus `origin` (the collider's origin now). Its Hessian is k I.
SHARED_FN VEC3 add_anchor_pull(VEC3 f, VEC3 x, VEC3 rel, VEC3 origin, REAL k) {
  PRECISE VEC3 anchor = rel + origin;
  PRECISE VEC3 r = f + (anchor - x) * k;
  return r;
}

// f plus the pull k (len - rest) n of a spring along its unit direction n (spring_terms's).
SHARED_FN VEC3 add_spring_pull(VEC3 f, VEC3 n, REAL len, REAL rest, REAL k) {
  PRECISE REAL magnitude = k * (len - rest);
  PRECISE VEC3 sum = f + n * magnitude;
  return sum;
}

// Provot's projection: a spring from xi to xj longer than `limit` is shortened to it, both ends
// moving by their share of the inverse mass (wsum = wi + wj > 0), the displacements with them
// (the ends' x_prev stay; a pinned end, w = 0, gets a zero correction). False, and nothing
// moves, if it is not longer.
SHARED_FN bool limit_stretch(INOUT(VEC3) xi, INOUT(VEC3) xj, INOUT(VEC3) di, INOUT(VEC3) dj, REAL wi, REAL wj, REAL wsum,
                             REAL limit) {
  VEC3 e = xj - xi;
  REAL len = length3(e);
  if (!(len > limit)) return false;
  PRECISE REAL excess = (len - limit) * (REAL(1) / len);
  PRECISE VEC3 corr = e * excess;
  PRECISE REAL inv_wsum = REAL(1) / wsum;
  PRECISE VEC3 ci = corr * (wi * inv_wsum);
  PRECISE VEC3 cj = corr * (wj * inv_wsum);
  PRECISE VEC3 nxi = xi + ci;
  PRECISE VEC3 nxj = xj - cj;
  PRECISE VEC3 ndi = di + ci;
  PRECISE VEC3 ndj = dj - cj;
  xi = nxi;
  xj = nxj;
  di = ndi;
  dj = ndj;
  return true;
}

// The pull of Provot's limit on one end (the multigrid sweep's, whose other end stays): the
// move of the end at xi (inverse mass wi; the other end's wj) along e = xj - xi when
// len = |e| > limit.
SHARED_FN VEC3 one_end_stretch_pull(VEC3 e, REAL len, REAL limit, REAL wi, REAL wj) {
  PRECISE REAL scale = (len - limit) * (REAL(1) / len) * (wi * (REAL(1) / (wi + wj)));
  PRECISE VEC3 corr = e * scale;
  return corr;
}

// v I, the inertia's block.
SHARED_FN SYM3 sym3_diagonal(REAL v) {
  SYM3 h;
  h.a = VEC3(v, REAL(0), REAL(0));
  h.b = VEC3(v, REAL(0), v);
  return h;
}

// k (n n^T (1 - t) + t I), t = max(0, 1 - rest/len): a spring's Hessian with its compressive
// part dropped (positive semi-definite), added to h as s n n^T + d I (spring_terms gives s, d).
SHARED_FN void add_spring_hessian(INOUT(SYM3) h, VEC3 n, REAL s, REAL d) {
  PRECISE REAL xx = h.a.x + (s * n.x * n.x + d);
  PRECISE REAL xy = h.a.y + s * n.x * n.y;
  PRECISE REAL xz = h.a.z + s * n.x * n.z;
  PRECISE REAL yy = h.b.x + (s * n.y * n.y + d);
  PRECISE REAL yz = h.b.y + s * n.y * n.z;
  PRECISE REAL zz = h.b.z + (s * n.z * n.z + d);
  h.a = VEC3(xx, xy, xz);
  h.b = VEC3(yy, yz, zz);
}

// (s n n^T + d I) v, a spring's Hessian times v.
SHARED_FN VEC3 spring_hessian_times(VEC3 n, REAL s, REAL d, VEC3 v) {
  PRECISE VEC3 hv = n * (s * dot3(n, v)) + v * d;
  return hv;
}

// The spring from p to q (rest `rest`, stiffness k): its unit direction n, its length and the
// Hessian's two coefficients s = k (1 - t) along n and d = k t across. Coincident ends: false,
// but for a zero-length spring (a sewn seam), whose Hessian k I has no direction to need: then
// d = k, n = 0 and the pull is zero (a welded pair stays coupled in the solve).
SHARED_FN bool spring_terms(VEC3 p, VEC3 q, REAL rest, REAL k, OUT(VEC3) n, OUT(REAL) len, OUT(REAL) s, OUT(REAL) d) {
  n = VEC3(REAL(0));
  s = REAL(0);
  d = REAL(0);
  PRECISE VEC3 e = q - p;
  len = length3(e);
  if (!(len > REAL(0))) {
    d = rest == REAL(0) ? k : REAL(0);
    return rest == REAL(0);
  }
  PRECISE REAL inv = REAL(1) / len;
  PRECISE VEC3 unit = e * inv;
  n = unit;
  PRECISE REAL t = max(REAL(0), REAL(1) - rest * inv);
  PRECISE REAL across = k * t;
  PRECISE REAL along = k - across;
  d = across;
  s = along;
  return true;
}

// h^-1 f by cofactors; false (and x = 0) if h is not positive definite in floating point.
SHARED_FN bool solve3(SYM3 h, VEC3 f, OUT(VEC3) x) {
  x = VEC3(REAL(0));
  REAL xx = h.a.x;
  REAL xy = h.a.y;
  REAL xz = h.a.z;
  REAL yy = h.b.x;
  REAL yz = h.b.y;
  REAL zz = h.b.z;
  PRECISE REAL c00 = yy * zz - yz * yz;
  PRECISE REAL c01 = xz * yz - xy * zz;
  PRECISE REAL c02 = xy * yz - xz * yy;
  PRECISE REAL det = (xx * c00 + xy * c01) + xz * c02;
  if (!(det > REAL(0))) return false;
  PRECISE REAL c11 = xx * zz - xz * xz;
  PRECISE REAL c12 = xy * xz - xx * yz;
  PRECISE REAL c22 = xx * yy - xy * xy;
  PRECISE REAL inv = REAL(1) / det;
  PRECISE VEC3 r = VEC3(((c00 * f.x + c01 * f.y) + c02 * f.z) * inv, ((c01 * f.x + c11 * f.y) + c12 * f.z) * inv,
                        ((c02 * f.x + c12 * f.y) + c22 * f.z) * inv);
  x = r;
  return true;
}

SHARED_END

#endif

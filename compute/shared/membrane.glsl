// The material's formulas (docs/materials.md, "How the model uses them"): a membrane
// triangle's, a bending row entry's and a curved hinge's force on one of its particles, and
// that particle's block of their Hessian, kept positive semi-definite (the sweep's Newton step
// needs it). Included by compute/relax_vertices.comp and compute/compute_residuals.comp through
// multigrid.glsl, and by host/core/reference/reference_material.hpp; the gathers stay with each
// backend.
#ifndef CLOTHSIM_SHARED_MEMBRANE_GLSL
#define CLOTHSIM_SHARED_MEMBRANE_GLSL

#include "springs.glsl"

SHARED_BEGIN

// Triangle (xi, xa, xb) seen from xi: dminv its rest [ua - ui, ub - ui]^-1 in the material's
// frame (row-major in x, y, z, w), `area` its rest area, moduli (C11, C22, b, G): the warp's and
// the weft's stretch and the shear (N/m), b the compression ratio. St Venant-Kirchhoff without
// Poisson coupling: F = [xa - xi, xb - xi] dminv, E = (F^T F - I) / 2, energy per area
// C11' E00^2 / 2 + C22' E11^2 / 2 + 2 G E01^2 (a shear angle g costs G g^2 / 2), where a
// direction shortened (E < 0) takes b times its stiffness: woven fabric buckles at its yarns
// under compression (docs/materials.md, "compression").
// Returns f - area F S g, g = dN_i = -(the rows of dminv summed); with `block`, adds
// area (max(0, g.S g) I + F M F^T) to h, M the elasticity contracted with g twice (the
// dropped part is the compressive one, as a spring's). The residual needs no block: without
// it the term costs half as much.
SHARED_FN_INLINE VEC3 add_membrane_terms(VEC3 f, INOUT(SYM3) h, VEC3 xi, VEC3 xa, VEC3 xb, VEC4 dminv, REAL area,
                                         VEC4 moduli, bool block) {
  PRECISE VEC3 ea = xa - xi;
  PRECISE VEC3 eb = xb - xi;
  PRECISE VEC3 f0 = ea * dminv.x + eb * dminv.z;
  PRECISE VEC3 f1 = ea * dminv.y + eb * dminv.w;
  PRECISE REAL e00 = (dot3(f0, f0) - REAL(1)) * REAL(0.5);
  PRECISE REAL e11 = (dot3(f1, f1) - REAL(1)) * REAL(0.5);
  PRECISE REAL e01 = dot3(f0, f1) * REAL(0.5);
  PRECISE REAL c11 = e00 < REAL(0) ? moduli.x * moduli.z : moduli.x;
  PRECISE REAL c22 = e11 < REAL(0) ? moduli.y * moduli.z : moduli.y;
  PRECISE REAL s00 = c11 * e00;
  PRECISE REAL s11 = c22 * e11;
  PRECISE REAL s01 = REAL(2) * moduli.w * e01;
  PRECISE REAL g0 = -(dminv.x + dminv.z);
  PRECISE REAL g1 = -(dminv.y + dminv.w);
  PRECISE REAL sg0 = s00 * g0 + s01 * g1;
  PRECISE REAL sg1 = s01 * g0 + s11 * g1;
  PRECISE VEC3 pg = f0 * sg0 + f1 * sg1;
  PRECISE VEC3 r = f - pg * area;
  if (!block) return r;
  PRECISE REAL d = max(REAL(0), g0 * sg0 + g1 * sg1) * area;
  PRECISE REAL m00 = (c11 * g0 * g0 + moduli.w * g1 * g1) * area;
  PRECISE REAL m11 = (moduli.w * g0 * g0 + c22 * g1 * g1) * area;
  PRECISE REAL m01 = moduli.w * (g0 * g1) * area;
  // F M F^T = m00 f0 f0^T + m11 f1 f1^T + m01 (f0 f1^T + f1 f0^T)
  PRECISE VEC3 a0 = f0 * m00 + f1 * m01;  // F M's columns
  PRECISE VEC3 a1 = f0 * m01 + f1 * m11;
  PRECISE REAL xx = h.a.x + ((a0.x * f0.x + a1.x * f1.x) + d);
  PRECISE REAL xy = h.a.y + (a0.x * f0.y + a1.x * f1.y);
  PRECISE REAL xz = h.a.z + (a0.x * f0.z + a1.x * f1.z);
  PRECISE REAL yy = h.b.x + ((a0.y * f0.y + a1.y * f1.y) + d);
  PRECISE REAL yz = h.b.y + (a0.y * f0.z + a1.y * f1.z);
  PRECISE REAL zz = h.b.z + ((a0.z * f0.z + a1.z * f1.z) + d);
  h.a = VEC3(xx, xy, xz);
  h.b = VEC3(yy, yz, zz);
  return r;
}

// A hinge seen from its particle at xs, its others at x0, x1, x2: v = k.x xs + k.y x0 + k.z x1 +
// k.w x2 (weights scaled so the energy is (|v| - rest)^2 / 2). Returns f - k.x (|v| - rest) v/|v|
// and adds k.x^2 ((1 - t) n n^T + t I), t = max(0, 1 - rest/|v|), to h: a spring in v's space
// (spring_terms), whose rest is the rest shape's curvature (0 on a flat cloth, where the energy
// is quadratic and the block k.x^2 I).
SHARED_FN VEC3 add_hinge_terms(VEC3 f, INOUT(SYM3) h, VEC3 xs, VEC3 x0, VEC3 x1, VEC3 x2, VEC4 k, REAL rest) {
  PRECISE VEC3 v = ((xs * k.x + x0 * k.y) + x1 * k.z) + x2 * k.w;
  PRECISE REAL k2 = k.x * k.x;
  VEC3 n;
  REAL len, sa, sd;
  if (!spring_terms(VEC3(REAL(0)), v, rest, k2, n, len, sa, sd)) return f;
  add_spring_hessian(h, n, sa, sd);
  PRECISE REAL magnitude = k.x * (len - rest);
  PRECISE VEC3 r = f - n * magnitude;
  return r;
}

// An entry q = Q_sj of the bending row of the particle at xs (ClothModel::bend): the flat
// stencils' energy 1/2 x^T Q x pulls it by -q (xj - xs) (the row sums to 0, so the differences
// keep the sum's rounding to the cloth's size rather than its distance from the origin). The
// row's first entry, the particle's own, adds exactly nothing; its block is Q_ss I throughout.
SHARED_FN VEC3 add_bend_pull(VEC3 f, VEC3 xs, VEC3 xj, REAL q) {
  PRECISE VEC3 r = f - (xj - xs) * q;
  return r;
}

SHARED_END

#endif

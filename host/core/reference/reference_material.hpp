// A material's terms on the CPU (docs/materials.md): the gathers of a particle's membrane
// triangles and bending stencils, which compute/multigrid.glsl makes on the GPU, over the
// formulas of compute/shared/membrane.glsl. Used by reference_multigrid.cpp's compute_residuals
// and relax_vertices.
#pragma once

#include "reference/reference.hpp"
#include "../../../compute/shared/membrane.glsl"

namespace clothsim {

// Particle i's membrane triangles, bending row and curved hinges at positions pos(j)
// (docs/materials.md): their forces added to f and their blocks to hess (the membrane's only
// with `block`), in that order, as the shaders do
// (add_material_terms in compute/multigrid.glsl).
template <class R, class Pos>
Vec3<R> add_material_terms(const ClothModel& m, const Constants<R>& c, uint32_t i, Vec3<R> x, Pos pos, Vec3<R> f,
                           shared::Sym3<R>& hess, bool block) {
  if (!m.has_material()) return f;
  const Vec4<R> moduli = c.materials[m.material[i]].moduli;
  for (uint32_t e = m.membrane_start[i]; e < m.membrane_start[i + 1]; ++e) {
    const MembraneEntry& t = m.membrane[e];
    const Vec4<R> dminv(R(t.dminv[0]), R(t.dminv[1]), R(t.dminv[2]), R(t.dminv[3]));
    f = shared::add_membrane_terms(f, hess, x, pos(t.a), pos(t.b), dminv, R(t.area), moduli, block);
  }
  const uint32_t first = m.bend_start[i], last = m.bend_start[i + 1];
  if (first < last) shared::add_spring_hessian(hess, Vec3<R>(R(0)), R(0), R(m.bend[first].weight));
  for (uint32_t e = first; e < last; ++e) f = shared::add_bend_pull(f, x, pos(m.bend[e].other), R(m.bend[e].weight));
  for (uint32_t e = m.hinge_start[i]; e < m.hinge_start[i + 1]; ++e) {
    const HingeEntry& h = m.hinges[e];
    const Vec4<R> k(R(h.k[0]), R(h.k[1]), R(h.k[2]), R(h.k[3]));
    f = shared::add_hinge_terms(f, hess, x, pos(h.other[0]), pos(h.other[1]), pos(h.other[2]), k, R(h.rest));
  }
  return f;
}

// Q_ii plus the sum of k0^2 over particle i's curved hinges, its bending block's diagonal at a
// flat rest (hinge_block in compute/multigrid.glsl). The coarse levels have no bending: a correction
// they compute for the bending's residual as if only the inertia resisted it overshoots the
// stiff bend of a fine cloth, so each mass enters them weighing that block too (docs/materials.md).
template <class R> R hinge_block(const ClothModel& m, uint32_t i, R sum) {
  if (!m.has_material()) return sum;
  if (m.bend_start[i] < m.bend_start[i + 1]) sum = R(m.bend[m.bend_start[i]].weight);
  for (uint32_t e = m.hinge_start[i]; e < m.hinge_start[i + 1]; ++e)
    sum = sum + R(m.hinges[e].k[0]) * R(m.hinges[e].k[0]);
  return sum;
}

}  // namespace clothsim

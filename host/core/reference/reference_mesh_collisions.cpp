// The reference's mesh colliders (docs/model.md, "Mesh colliders"): a mass against a mesh's
// signed distance field. The formulas are compute/shared/mesh_field.glsl's; reading the nodes
// and walking a path stay here (compute/collide_meshes.glsl does the same on the GPU).
#include <algorithm>
#include <cmath>

#include "colliders/mesh_collider.hpp"
#include "reference/reference.hpp"
#include "reference/reference_detail.hpp"
#include "../../../compute/shared/mesh_field.glsl"

namespace clothsim {
namespace {

template <class R> Vec3<R> to_local(const MeshColliderT<R>& m, const Vec3<R>& v) {
  return shared::to_local(Vec3<R>(m.row0), Vec3<R>(m.row1), Vec3<R>(m.row2), v);
}
template <class R> Vec3<R> to_world(const MeshColliderT<R>& m, const Vec3<R>& v) {
  return shared::to_world(Vec3<R>(m.row0), Vec3<R>(m.row1), Vec3<R>(m.row2), v);
}

}  // namespace

template <class R> bool sample_mesh_field(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& p, R& phi, Vec3<R>& grad) {
  Vec3<R> g;
  if (!shared::inside_grid(p, Vec3<R>(m.grid), m.grid.w, Vec3<R>(glm::ivec3(m.dims) - 1), g)) return false;
  const Vec3<R> cell(std::floor(g.x), std::floor(g.y), std::floor(g.z));
  const Vec3<R> f = g - cell;
  const int nx = m.dims.x, nxy = m.dims.x * m.dims.y;
  const int base = m.dims.w + int(cell.x) + nx * int(cell.y) + nxy * int(cell.z);
  const R c000 = R(sdf[base]), c100 = R(sdf[base + 1]), c010 = R(sdf[base + nx]), c110 = R(sdf[base + nx + 1]);
  const R c001 = R(sdf[base + nxy]), c101 = R(sdf[base + nxy + 1]), c011 = R(sdf[base + nxy + nx]),
          c111 = R(sdf[base + nxy + nx + 1]);
  phi = shared::trilinear(c000, c100, c010, c110, c001, c101, c011, c111, f, grad);
  return true;
}

template <class R> Vec3<R> mesh_local_point(const MeshColliderT<R>& m, const Vec3<R>& x) {
  return to_local(m, x - mesh_origin(m));
}

template <class R> bool sample_mesh_at(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& x, R& phi, Vec3<R>& grad) {
  return sample_mesh_field(m, sdf, mesh_local_point(m, x), phi, grad);
}

template <class R> MeshColliderT<R> make_mesh_collider(const MeshColliderParams& p, const SdfGrid& g, uint32_t offset) {
  const glm::dmat3 rot = collider_rotation(p);
  // Column r of R is row r of its transpose; w the origin.
  MeshColliderT<R> m{};
  m.row0 = Vec4<R>(Vec3<R>(rot[0]), R(p.origin.x));
  m.row1 = Vec4<R>(Vec3<R>(rot[1]), R(p.origin.y));
  m.row2 = Vec4<R>(Vec3<R>(rot[2]), R(p.origin.z));
  m.grid = Vec4<R>(Vec3<R>(g.min), R(1.0 / g.voxel));
  m.dims = glm::ivec4(g.dims, int(offset));
  m.motion = Vec4<R>(Vec3<R>(0), R(1.0 - p.friction));  // w keep
  // mu, thickness, crossing, closed
  m.material = Vec4<R>(R(p.friction), R(p.thickness), R(0.5 * p.thickness), g.closed ? R(1) : R(0));
  return m;
}

namespace {

template <class R> bool world_normal(const MeshColliderT<R>& m, const Vec3<R>& grad, Vec3<R>& n) {
  return shared::world_normal(Vec3<R>(m.row0), Vec3<R>(m.row1), Vec3<R>(m.row2), grad, n);
}

// A mass outside the offset surface at the end of the substep that moved by rel (relative to
// the mesh) further than its clearance: its path is sampled every half node spacing (at most 8
// samples). A closed mesh: a sample inside it means the mass went through a wall within the
// substep. An open mesh (its field signed by the winding number): a sample past the start
// inside it, or two neighbouring samples that straddle the shell of a thin sheet, where the
// field stays unsigned (shared::crossed_open_mesh).
// Either way t - x is the way back to the sample before, on the side it came from.
template <class R>
bool passed_through_mesh(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& p, R phi, const Vec3<R>& rel,
                         Vec3<R>& t_minus_x) {
  const R moved = length3(rel);
  if (shared::stays_clear_of_mesh(moved, phi, m.material.y)) return false;  // y: thickness
  const bool closed = m.material.w != R(0);
  const Vec3<R> step_all = to_local(m, rel);
  const int samples = shared::path_samples(moved, m.grid.w);
  const R spacing = moved * (R(1) / R(samples));
  const Vec3<R> start = p - step_all;
  R prev_phi = R(0), prev_slope = R(0);
  bool prev_in_grid = false;
  // A closed mesh's path starts and ends outside it: its ends are not sampled.
  const int first = closed ? 1 : 0, last = closed ? samples - 1 : samples;
  for (int k = first; k <= last; ++k) {
    const Vec3<R> q = start + step_all * (R(k) / R(samples));
    R phi_q;
    Vec3<R> grad;
    const bool in_grid = sample_mesh_field(m, sdf, q, phi_q, grad);
    bool crossed = false;
    if (closed) {
      crossed = in_grid && phi_q < R(0);
    } else if (in_grid) {
      const R slope = dot3(grad, step_all);
      crossed = shared::crossed_open_mesh(k, prev_in_grid, prev_slope, slope, prev_phi, phi_q, spacing, m.material.z);
      prev_phi = phi_q;
      prev_slope = slope;
    }
    prev_in_grid = in_grid;
    if (!crossed) continue;
    const Vec3<R> back = start + step_all * (R(k - 1) / R(samples));
    t_minus_x = to_world(m, back - p);
    return true;
  }
  return false;
}

}  // namespace

template <class R> void keep_out_of_mesh(const Constants<R>& c, const MeshColliderT<R>& m, Vec3<R>& x, Vec3<R>& d) {
  R phi;
  Vec3<R> grad, n;
  if (!sample_mesh_at(m, c.sdf->data(), x, phi, grad)) return;
  const R depth = m.material.y - phi;  // below the thickness
  if (!(depth > R(1e-4)) || !world_normal(m, grad, n)) return;
  shared::push_out_of_mesh(n, depth, x, d);
}

template <class R> void collide_with_mesh(const Constants<R>& c, const MeshColliderT<R>& m, bool friction, Vec3<R>& x, Vec3<R>& d) {
  const float* sdf = c.sdf->data();
  const Vec3<R> p = to_local(m, x - mesh_origin(m));
  R phi;
  Vec3<R> grad, n, t_minus_x;
  if (!sample_mesh_field(m, sdf, p, phi, grad)) return;
  if (phi < m.material.y) {
    // In contact: out along the field's gradient to the offset surface.
    if (!world_normal(m, grad, n)) return;
    t_minus_x = n * (m.material.y - phi);
  } else {
    if (!passed_through_mesh(m, sdf, p, phi, d - Vec3<R>(m.motion), t_minus_x)) return;
    // The normal of the contact is the field's where the mass is put back.
    R phi_back;
    Vec3<R> grad_back;
    if (!sample_mesh_field(m, sdf, p + to_local(m, t_minus_x), phi_back, grad_back) || !world_normal(m, grad_back, n))
      n = t_minus_x * (R(1) / length3(t_minus_x));
  }
  respond_to_contact(friction && c.multigrid, t_minus_x, n, friction ? m.motion.w : R(1), m.material.x, Vec3<R>(m.motion), x, d);
  keep_out_of_mesh(c, m, x, d);
}

#define CLOTHSIM_INSTANTIATE(R)                                                                          \
  template bool sample_mesh_field<R>(const MeshColliderT<R>&, const float*, const Vec3<R>&, R&, Vec3<R>&);        \
  template Vec3<R> mesh_local_point<R>(const MeshColliderT<R>&, const Vec3<R>&);                                  \
  template bool sample_mesh_at<R>(const MeshColliderT<R>&, const float*, const Vec3<R>&, R&, Vec3<R>&);           \
  template MeshColliderT<R> make_mesh_collider<R>(const MeshColliderParams&, const SdfGrid&, uint32_t);           \
  template void keep_out_of_mesh<R>(const Constants<R>&, const MeshColliderT<R>&, Vec3<R>&, Vec3<R>&);           \
  template void collide_with_mesh<R>(const Constants<R>&, const MeshColliderT<R>&, bool, Vec3<R>&, Vec3<R>&);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

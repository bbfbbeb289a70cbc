// The mesh colliders' fields as the GPU reads them (compute/collide_meshes.glsl,
// sample_mesh_field): texel k holds node k's value and those of its +x, +y and +x+y
// neighbours, so a trilinear sample is two texel fetches (the cell's lower and upper xy faces)
// instead of eight. The values are the reference's floats, moved, never recomputed, so both
// backends still interpolate the same bits. Four times the memory of the fields (one RGBA32F
// texel per node where the reference keeps one float); on llvmpipe a texel fetch is a call to
// a generated function, and the eight made a field sample the dearest part of the colliders.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <glm/vec4.hpp>

#include "reference/reference.hpp"

namespace clothsim {

// `fields`: every mesh's nodes, concatenated (Constants::sdf), mesh m's from meshes[m].dims.w,
// x fastest. A neighbour past the field's last x or y node is 0: no cell that sample_mesh_field
// reads has its lower corner there.
inline std::vector<glm::vec4> sdf_cell_texels(const std::vector<float>& fields, const std::vector<layout::MeshCollider>& meshes) {
  std::vector<glm::vec4> texels(fields.size(), glm::vec4(0.f));
  for (const layout::MeshCollider& m : meshes) {
    const size_t nx = size_t(m.dims.x), ny = size_t(m.dims.y), nz = size_t(m.dims.z);
    for (size_t z = 0; z < nz; ++z)
      for (size_t y = 0; y < ny; ++y)
        for (size_t x = 0; x < nx; ++x) {
          const size_t k = size_t(m.dims.w) + x + nx * (y + ny * z);
          const bool right = x + 1 < nx, up = y + 1 < ny;
          texels[k] = glm::vec4(fields[k], right ? fields[k + 1] : 0.f, up ? fields[k + nx] : 0.f,
                                right && up ? fields[k + nx + 1] : 0.f);
        }
  }
  return texels;
}

// Each mesh's field slope bound in the world (MeshCollider::bound.x; the contact list's
// mesh_leaves_alone_after): with D the largest difference between neighbouring nodes along each
// axis, every partial derivative of the trilinear interpolant is a blend of such differences over
// the spacing, so |grad| <= |D| / spacing and the sampled field is that Lipschitz, across cells
// and out of the grid as the shaders extend it. Measured, not assumed 1 or sqrt(3): an open
// mesh's unsigned field, the clamping of the far field, anything the builder does, is covered.
// Rounded up to the next float.
inline std::vector<float> sdf_slopes(const std::vector<float>& fields, const std::vector<layout::MeshCollider>& meshes) {
  std::vector<float> slopes;
  for (const layout::MeshCollider& m : meshes) {
    const size_t nx = size_t(m.dims.x), ny = size_t(m.dims.y), nz = size_t(m.dims.z);
    double dx = 0, dy = 0, dz = 0;
    for (size_t z = 0; z < nz; ++z)
      for (size_t y = 0; y < ny; ++y)
        for (size_t x = 0; x < nx; ++x) {
          const size_t k = size_t(m.dims.w) + x + nx * (y + ny * z);
          const double v = fields[k];
          if (x + 1 < nx) dx = std::max(dx, std::abs(double(fields[k + 1]) - v));
          if (y + 1 < ny) dy = std::max(dy, std::abs(double(fields[k + nx]) - v));
          if (z + 1 < nz) dz = std::max(dz, std::abs(double(fields[k + nx * ny]) - v));
        }
    const double slope = double(m.grid.w) * std::sqrt(dx * dx + dy * dy + dz * dz);
    slopes.push_back(std::nextafter(float(slope), std::numeric_limits<float>::infinity()));
  }
  return slopes;
}

}  // namespace clothsim

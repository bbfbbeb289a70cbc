// What fabric_terms.cpp and mesh_plate.cpp share: a triangle's rest frame in the material's
// directions and the bending stencils being collected (docs/materials.md).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cloth/cloth.hpp"

namespace clothsim {

// A triangle's rest frame: unit warp u (along the texture's u, or the first edge where the
// texture gives none), weft v = n x u, and its corners' coordinates in it (metres).
struct TriangleFrame {
  glm::dvec3 u{0.0}, v{0.0};
  glm::dvec2 q[3];
  double area = 0;
};

// Every bending stencil of the cloths, per particle: the flat ones summed into Q's rows, the
// curved ones as hinge entries (cloth.hpp, BendEntry and HingeEntry).
struct Stencils {
  std::vector<std::map<uint32_t, double>> rows;
  std::vector<std::vector<HingeEntry>> hinges;
};

// One bending stencil: v = sum w_k x_k over its particles, energy (|v| - rest)^2 / 2: with a
// flat rest its w w^T into Q, else an entry of each of its particles (at most four).
void add_stencil(Stencils& out, const std::vector<uint32_t>& v, const std::vector<double>& w, double rest);

// A flat mesh's bending (mesh_plate.cpp): the orthotropic plate of a grid's stencils, its
// curvatures the second derivatives of a quadratic fitted to each inner vertex's ring.
void add_mesh_plate_stencils(const ClothModel& m, const ClothPart& part, const MaterialParams& mat,
                             const std::vector<TriangleFrame>& frames, Stencils& out);

}  // namespace clothsim

// The generalised winding number of a triangle mesh (Jacobson et al. 2013), fast: the
// triangles in a bounding-volume tree, each cluster far from the query point replaced by its
// dipole, the sum of its area vectors at their area-weighted centre (Barill et al. 2018, "Fast
// winding numbers for soups and clouds", first order). Near clusters are summed exactly.
//
// What it is for: inside and outside of meshes with holes. A closed mesh's winding number is
// 1 inside and 0 outside; an open one's falls smoothly from 1 to 0 across each hole, so
// "inside" is where it is above 1/2, the hole closed by that level set. The open mesh colliders'
// fields are signed by it (sdf.cpp), and --stats counts the masses inside each mesh collider by it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "colliders/sdf.hpp"

namespace clothsim {

class FastWindingNumber {
 public:
  // `accuracy` (beta): a cluster is approximated when the point is further than beta times its
  // radius from its centre; 2 gives about 1e-3 of the exact sum (tests).
  explicit FastWindingNumber(const SurfaceMesh& mesh, double accuracy = 2.0);
  // The winding number at p, with the mesh's own winding (1 inside a counter-clockwise-from-
  // outside closed mesh, -1 inside one wound the other way).
  double operator()(const glm::dvec3& p) const;

 private:
  struct Node {
    glm::dvec3 centre{0.0};       // area-weighted centroid of its triangles
    glm::dvec3 area_vector{0.0};  // sum of (b - a) x (c - a) / 2
    double radius2 = 0;           // (beta * the furthest vertex from the centre)^2
    uint32_t first = 0, count = 0;  // its triangles in order_ (a leaf), or
    int32_t left = -1, right = -1;  // its children
  };
  int32_t build(uint32_t first, uint32_t count, double beta);
  std::vector<glm::dvec3> a_, b_, c_;  // the triangles' corners, in tree order
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

// The field of an open mesh (build_sdf): `g.values` set from the band's nearest triangle and
// squared distance per node (-1: beyond the band), negative where the winding number is above
// 1/2 in magnitude.
void sign_by_winding(const SurfaceMesh& mesh, SdfGrid& g, const std::vector<int32_t>& nearest,
                     const std::vector<double>& dist2);

// The exact signed solid angle of triangle (a, b, c) seen from the origin, over 4 pi (Van
// Oosterom and Strackee 1983): one triangle's share of the winding number.
double triangle_winding(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace clothsim

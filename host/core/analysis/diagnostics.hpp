// What a run reports about the cloth: stretch, energy, clearance to colliders (divergence:
// divergence.hpp).
// Works on double copies of any backend's state.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "cloth/cloth.hpp"
#include "scene/scene.hpp"

namespace clothsim {

struct ClothSnapshot {
  std::vector<glm::dvec4> pos;   // w = inverse mass
  std::vector<glm::dvec4> disp;  // displacement of the last substep, x - x_prev
  std::vector<glm::dvec4> normal;     // may be empty
};

struct ClothStats {
  double max_stretch_ratio = 0;  // max over springs of length / rest length (seams are no edge: left out)
  double p99_stretch_ratio = 0;  // its 99th percentile (the ratio 99 % of the springs are at or under)
  double kinetic = 0;            // J, from the Verlet velocity d / dt, d = x - x_prev
  double gravitational = 0;      // J, -m g . x summed
  double spring = 0;             // J, 1/2 k (len - rest)^2 over enabled springs (seams: at zero rest)
  size_t seam_pairs = 0;         // sewn pairs (cloth.seams)
  double max_seam_gap = 0;       // m, the widest of their distances
  // Where each collider is at the snapshot's time (a keyframed one at its keyframed position):
  std::vector<double> sphere_clearance;  // min |x - o| - r per sphere (negative: inside)
  std::vector<double> plane_clearance;   // min signed distance on the plane's front (the cloth's starting side), per plane
  std::vector<double> mesh_clearance;    // min field distance to the surface per mesh collider (negative: inside; at most its band)
  std::vector<size_t> mesh_inside;       // masses inside each mesh collider by its winding number (> 1/2), holes and all
  double max_speed = 0;          // m/s
  bool finite = true;
  double total_energy() const { return kinetic + gravitational + spring; }
};

// `time`: the simulated seconds of the snapshot (Backend::time()), where the keyframed colliders
// (scene.spheres[k].motion, planes[k].motion) are measured from; the static ones ignore it.
ClothStats measure(const Scene& scene, const ClothModel& model, const ClothSnapshot& s, double time = 0);

// Wavefront OBJ: v in particle order, vt, vn, then the triangles of §1 (1-based).
void write_obj(const std::string& path, const ClothModel& model, const ClothSnapshot& s);

}  // namespace clothsim

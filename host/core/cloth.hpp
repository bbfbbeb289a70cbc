// The cloth built from a scene (DESIGN.md §1 "Cloth construction"): the part that never
// changes during a run. Springs are implicit in the grid: the spring from (x, y) to
// (x + dx, y + dy) of direction d exists when both ends are on the grid, and its rest
// length is stored at (x, y). This is the same shape the GPU buffers have.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene.hpp"
#include "spring_grid.hpp"

namespace clothsim {

struct ClothModel {
  int nw = 0, nh = 0;                 // grid size (num_width_points x num_height_points)
  double mass = 0;                    // of every particle, kg
  std::vector<glm::dvec3> initial;    // start positions, row-major i = y * nw + x
  std::vector<uint8_t> pinned;        // 1 = never moves
  std::vector<std::array<double, NUM_DIRECTIONS>> rest;  // rest length per stored direction (0 = no spring)
  std::vector<std::array<uint32_t, 3>> triangles;         // (A, C, B), (B, C, D) per cell
  std::vector<glm::dvec2> uv;
  // xpbd's long-range attachments (tethers.cpp): each particle's nearest pin along the rest
  // cloth (-1: none, for pins and for a cloth without pins) and the distance to it.
  std::vector<int32_t> tether_pin;
  std::vector<double> tether_rest;

  int count() const { return nw * nh; }
  int index(int x, int y) const { return y * nw + x; }
  // Spring counts by type, all directions (independent of enable_* flags).
  int structural_springs() const { return (nw - 1) * nh + nw * (nh - 1); }
  int shearing_springs() const { return 2 * (nw - 1) * (nh - 1); }
  int bending_springs() const { return (nw - 2) * nh + nw * (nh - 2); }
  int springs() const { return structural_springs() + shearing_springs() + bending_springs(); }
};

ClothModel build_cloth(const ClothParams& params);
void build_tethers(ClothModel& model);  // called by build_cloth

// Mass of every particle: width * height * density / particle count (kg).
double particle_mass(const ClothParams& params);

// The z offset of a vertical cloth's particle i, in [-amplitude, amplitude]: a hash of the
// index, so the same cloth comes out on every machine and both backends (no std:: distribution).
double vertical_offset(uint32_t i, double amplitude);
// The amplitude for a grid spacing: 1e-3 m (the classic), at most 5 % of the spacing.
double jitter_amplitude(double spacing);

}  // namespace clothsim

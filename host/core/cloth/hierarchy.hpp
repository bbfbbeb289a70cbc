// The multigrid solver's hierarchy (docs/model.md, "One substep (fabric solver)"): coarser and
// coarser clouds of the cloth's own particles, each joined by springs of its own, built once from
// the cloth model's rest shape. Grids and meshes coarsen alike: a level's vertices are a maximal
// independent set of the finer level's graph, so on a CS184 grid every second particle of every
// second row (the interpolation then is exactly bilinear), on a mesh the like.
#pragma once

#include <cstdint>
#include <vector>

#include "cloth/cloth.hpp"

namespace clothsim {

// One coarse level: vertices [first, first + count) of the hierarchy's global coarse numbering,
// coloured so that no coarse spring joins two vertices of one colour (one dispatch per colour).
struct HierarchyLevel {
  uint32_t first = 0, count = 0;
  // Colour k is order[colour_start[k] .. colour_start[k + 1]) (global coarse indices).
  std::vector<uint32_t> colour_start;
};

struct Hierarchy {
  // The fine sweep (relax_vertices): the cloth's particles coloured so that no spring of any type
  // joins two of one colour; colour k is fine_order[fine_colour_start[k] .. [k + 1]).
  std::vector<uint32_t> fine_colour_start, fine_order;
  std::vector<uint32_t> fine_colour;  // per particle: its colour in that sweep
  // Per particle, its parents on level 1 (global coarse indices) and their weights (1 / count:
  // a coarse particle's only parent is itself; on a grid, bilinear interpolation).
  std::vector<uint32_t> fine_parent_start, fine_parent;
  std::vector<double> fine_parent_weight;

  // Per coarse vertex (global index):
  std::vector<uint32_t> particle;  // the cloth particle it sits on (its position, its pinned flag)
  // Its children on the next finer level with the weight each gives it, the transpose of the
  // finer level's parents: the restriction. A child is an index into the residuals (State::
  // residual): a particle i for level 1, particle count + global coarse index deeper.
  std::vector<uint32_t> child_start, child;
  std::vector<double> child_weight;
  // Its parents on the next coarser level (none on the coarsest): the prolongation.
  std::vector<uint32_t> parent_start, parent;
  std::vector<double> parent_weight;
  // Its springs, gathered per vertex (each spring at both ends, in ascending order of the other
  // end): the other end (global index), the rest length, the stiffness (N/m).
  std::vector<uint32_t> spring_start, spring_other;
  std::vector<double> spring_rest, spring_k;
  std::vector<uint32_t> order;  // every level's vertices by colour (HierarchyLevel::colour_start)

  std::vector<HierarchyLevel> levels;  // levels[0] is level 1, the first coarse one
  std::vector<double> ks;  // the cloths' ks it was built for (its coarse springs follow them)

  uint32_t coarse_count() const { return uint32_t(particle.size()); }
  int fine_colours() const { return int(fine_colour_start.size()) - 1; }
};

// What build_hierarchy stops at: a level of at most this many vertices is the coarsest.
inline constexpr uint32_t kCoarsestVertices = 64;
// A coarse spring's stiffness over the cloth's ks: a regular grid's structural, shearing and
// bending springs resist a uniform stretch as 1.4 ks per unit area and a shear as 1.0 ks, the
// coarse level's structural and shearing springs both as its own k, so k = 1.2 ks errs by at
// most 17 % either way (docs/model.md works it out).
inline constexpr double kCoarseStiffness = 1.2;

// The hierarchy of `model` with stiffness ks per cloth (Scene::cloths() order). Deterministic:
// the same on every machine, for both backends.
Hierarchy build_hierarchy(const ClothModel& model, const std::vector<double>& ks);

}  // namespace clothsim

// Self-intersections of a cloth, counted exactly (simulate --stats, "self-intersections").
//
// The rule. Two triangles are counted when
//   * they share no vertex (index): triangles sharing a vertex or an edge are adjacent in the
//     mesh, always touch, and are never counted, however they overlap;
//   * their closed triangles intersect: any common point counts, so a triangle touching
//     another at a single point or along a segment is an intersection, and so is a coplanar
//     pair whose closed triangles meet (overlapping areas, or touching at an edge or corner).
//     A coplanar pair with no common point is not.
// Triangles of different cloths (parts) count like any others. Skipped (never counted, never
// tested): degenerate triangles (exactly zero area, e.g. a repeated index or three collinear
// points) and triangles with a non-finite (NaN or infinite) vertex.
//
// Exactness. Every decision is a sign of an orientation determinant (orient3d, and orient2d
// for coplanar pairs), evaluated in double with a forward error bound (Shewchuk's static
// filter) and, when the double result is within its bound, again exactly with floating-point
// expansions (error-free two-sum and Dekker two-product), so the answer is the one of exact
// real arithmetic on the given doubles. The pair test is Devillers and Guigue's (2002) on
// those predicates, with the coplanar case the 2D separating-edge test; nearly coplanar pairs
// are first offered a quick "no" (apart along an in-plane axis by far more than any rounding),
// which is certain too. Exact as long as no product of coordinate differences overflows or
// underflows, i.e. for finite coordinates of magnitude below about 1e60 whose non-zero
// differences exceed about 1e-60 (any cloth).
//
// The search. A uniform spatial hash of the triangles' bounding boxes, cells of twice the
// mean edge length: each triangle is entered in every cell its box overlaps, and a pair is
// tested once, in the first cell (lowest x, y, z) their boxes share. A triangle whose box
// spans more than 64 cells (or lies far outside any sensible grid) is kept in a separate list
// and tested against every other triangle. Single-threaded; the result is deterministic.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "cloth/cloth.hpp"
#include "analysis/diagnostics.hpp"

namespace clothsim {

// The number of unordered pairs of triangles that share no vertex and intersect (the rule
// above). Throws std::invalid_argument for a vertex index out of range of `positions`.
size_t count_self_intersections(const std::vector<std::array<uint32_t, 3>>& triangles,
                                const std::vector<glm::dvec3>& positions);
// Convenience: the model's triangles at a snapshot's positions (xyz of pos). Throws
// std::invalid_argument when the snapshot has not one position per particle.
size_t count_self_intersections(const ClothModel& model, const ClothSnapshot& snapshot);

// The exact predicates and the pair test, exposed for the tests.
namespace exact {
// The sign (-1, 0, +1) of det[b - a, c - a, d - a]: positive when d lies on the side of the
// plane abc that (b - a) x (c - a) points to.
int orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d);
// The sign of (b - a) x (c - a) in the plane of coordinates (i, j) (0 = x, 1 = y, 2 = z):
// positive when a, b, c turn counter-clockwise seen with i right and j up.
int orient2d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int i, int j);
// True when the triangle has exactly zero area (all three of its projections are degenerate).
bool degenerate(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
// Whether the closed triangles (a1, b1, c1) and (a2, b2, c2) have a common point; both must
// be non-degenerate. Knows nothing of shared indices: two triangles with a common vertex
// position always intersect here.
bool triangles_intersect(const glm::dvec3& a1, const glm::dvec3& b1, const glm::dvec3& c1, const glm::dvec3& a2,
                         const glm::dvec3& b2, const glm::dvec3& c2);
}  // namespace exact

}  // namespace clothsim

// The springs of a polygon-mesh cloth, as Blender's cloth and the CS184 grid make them:
//
// * structural: one per face edge (triangles and quads alike);
// * shearing: both diagonals of every quad;
// * bending: on quads, between vertices two steps apart along a line of edges: for an edge
//   (v, a) of a quad and another quad edge (a, b) that shares no face with (v, a), the spring
//   (v, b). On a regular grid that is exactly (x, y)-(x+2, y) and (x, y)-(x, y+2); at a
//   vertex of valence 5 a line has two continuations (both are taken), at valence 3 none.
//   On triangles: across every edge shared by two triangles, between the two vertices
//   opposite it. An edge between a quad and a triangle bends neither way.
//
// For a regular grid written row major with faces (x,y) (x+1,y) (x+1,y+1) (x,y+1) the three
// sets equal the CS184 grid's (tests/test_mesh_import.cpp checks it).
//
// Order, deterministic: each list in order of first discovery, walking the faces in order
// and each face's corners in order (edge k runs from corner k to corner k+1; a quad's
// diagonals are (0, 2) then (1, 3); an edge's bending springs are found from its first
// corner's side, then from its second's; a triangle pair's spring runs from the vertex of
// the face met first). Each spring keeps the direction it was found in (first particle:
// where it was found). An unordered pair appears once in all three lists together: the
// structural list is made first, then shearing, then bending, each skipping pairs already
// taken (on a grid no pair is in two lists). A pair (v, v) is never made.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cloth/mesh_import.hpp"

namespace clothsim {

struct MeshSprings {
  std::vector<std::array<uint32_t, 2>> structural, shearing, bending;  // particle pairs, no duplicates
};

// Throws std::invalid_argument for a face that is not 3 or 4 indices within the particles,
// or an edge in more than two faces (load_mesh never returns such a mesh).
MeshSprings build_mesh_springs(const PolyMesh& mesh);

}  // namespace clothsim

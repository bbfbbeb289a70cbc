// How the CS184 grid's springs and their colours follow from (x, y): the grid builder
// (cloth_grid.cpp) turns them into the model's explicit spring lists, and tests check the
// lists against them. The passes never see a grid: they read the lists.
#pragma once

#include <array>

#include "cloth/cloth.hpp"

namespace clothsim {

// Spring directions stored at their "first" particle: the spring from (x, y) to (x + dx, y + dy).
// The other six directions of a particle's twelve springs are these seen from the far end.
enum : int { DIR_RIGHT, DIR_DOWN, DIR_DIAG_DOWN_RIGHT, DIR_DIAG_DOWN_LEFT, DIR_RIGHT2, DIR_DOWN2, NUM_DIRECTIONS };
// Two colours per direction: no two springs of one colour share a particle.
inline constexpr int kGridColours = 12;

struct Direction {
  int dx, dy;
  SpringType type;  // directions come in pairs of one type
};

inline constexpr std::array<Direction, NUM_DIRECTIONS> kDirections{{
    {1, 0, SpringType::Structural}, {0, 1, SpringType::Structural},
    {1, 1, SpringType::Shearing}, {-1, 1, SpringType::Shearing},
    {2, 0, SpringType::Bending}, {0, 2, SpringType::Bending},
}};

// Colour of the spring of `direction` stored at (x, y): 2 * direction + parity. For unit steps
// the parity of the coordinate the spring advances along separates springs that share an end;
// two-steps need (coord / 2) % 2. Diagonals advance in y.
constexpr int spring_colour(int direction, int x, int y) {
  return 2 * direction + (direction == DIR_RIGHT    ? (x & 1)
                          : direction == DIR_RIGHT2 ? ((x >> 1) & 1)
                          : direction == DIR_DOWN2  ? ((y >> 1) & 1)
                                                    : (y & 1));
}

// One of a particle's twelve springs, in the fixed order the classic force gather sums them:
// for each direction, first the spring stored here (to x + d), then the one stored at x - d.
struct SpringRef {
  int direction;
  int sign;  // +1: stored at this particle; -1: stored at the neighbour (x - d)
};

inline constexpr std::array<SpringRef, 2 * NUM_DIRECTIONS> kGatherOrder{{
    {DIR_RIGHT, 1}, {DIR_RIGHT, -1}, {DIR_DOWN, 1}, {DIR_DOWN, -1},
    {DIR_DIAG_DOWN_RIGHT, 1}, {DIR_DIAG_DOWN_RIGHT, -1}, {DIR_DIAG_DOWN_LEFT, 1}, {DIR_DIAG_DOWN_LEFT, -1},
    {DIR_RIGHT2, 1}, {DIR_RIGHT2, -1}, {DIR_DOWN2, 1}, {DIR_DOWN2, -1},
}};

constexpr bool in_grid(int x, int y, int nw, int nh) { return x >= 0 && y >= 0 && x < nw && y < nh; }

}  // namespace clothsim

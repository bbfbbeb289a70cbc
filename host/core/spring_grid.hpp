// How springs and their colours follow from the grid, shared by the CPU reference and
// the host side of the GPU path. The GLSL side mirrors this in compute/spring_grid.glsl.
#pragma once

#include <array>

#include "../../compute/layout.glsl"

namespace clothsim {

enum class SpringType { Structural = 0, Shearing = 1, Bending = 2 };

struct Direction {
  int dx, dy;
  SpringType type;
};

// Indexed by DIR_* from layout.glsl.
inline constexpr std::array<Direction, NUM_DIRECTIONS> kDirections{{
    {1, 0, SpringType::Structural},
    {0, 1, SpringType::Structural},
    {1, 1, SpringType::Shearing},
    {-1, 1, SpringType::Shearing},
    {2, 0, SpringType::Bending},
    {0, 2, SpringType::Bending},
}};

// One of a particle's twelve springs, in the fixed order the force gather sums them:
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

// Colour of the spring of `direction` stored at (x, y). Colour c = 2 * direction + parity;
// for unit steps the parity of the coordinate the spring advances along separates springs
// that share an end; two-steps need (coord / 2) % 2. Diagonals advance in y.
constexpr int spring_colour(int direction, int x, int y) {
  switch (direction) {
    case DIR_RIGHT: return 2 * direction + (x & 1);
    case DIR_RIGHT2: return 2 * direction + ((x >> 1) & 1);
    case DIR_DOWN2: return 2 * direction + ((y >> 1) & 1);
    default: return 2 * direction + (y & 1);
  }
}

constexpr bool in_grid(int x, int y, int nw, int nh) { return x >= 0 && y >= 0 && x < nw && y < nh; }

}  // namespace clothsim

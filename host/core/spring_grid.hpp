// How springs and their colours follow from the grid, for the CPU reference and the host
// side of the GPU path. The offsets, types and colours are written once, for both languages,
// in compute/spring_grid.glsl; this header makes tables of them.
#pragma once

#include <array>

#include "../../compute/layout.glsl"
#include "../../compute/spring_grid.glsl"

namespace clothsim {

enum class SpringType { Structural = 0, Shearing = 1, Bending = 2 };

struct Direction {
  int dx, dy;
  SpringType type;
};

// Indexed by DIR_* from layout.glsl.
inline constexpr std::array<Direction, NUM_DIRECTIONS> kDirections = [] {
  std::array<Direction, NUM_DIRECTIONS> table{};
  for (int d = 0; d < NUM_DIRECTIONS; ++d)
    table[d] = {shared::direction_dx(d), shared::direction_dy(d), SpringType(shared::direction_type(d))};
  return table;
}();

using shared::spring_colour;

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

constexpr bool in_grid(int x, int y, int nw, int nh) { return x >= 0 && y >= 0 && x < nw && y < nh; }

// The springs of one colour, as a product of an x set and a y set, so the GPU can dispatch
// exactly those springs (count.x by count.y invocations) instead of every particle with half
// of them idle. On one axis, invocation i maps to
//   v = first + period * (i >> shift) + (i & ((1 << shift) - 1)):
// every coordinate (period 0, shift 30), every other one (period 2, shift 0), or pairs
// every four (period 4, shift 1) for the two-step bending springs.
struct AxisSpan {
  int first = 0, period = 0, shift = 30, count = 0;
  constexpr int at(int i) const { return first + period * (i >> shift) + (i & ((1 << shift) - 1)); }
};

struct ColourSpan {
  AxisSpan x, y;
};

// The span of `colour` on an nw x nh grid: the (x, y) where its springs are stored.
constexpr ColourSpan colour_span(int colour, int nw, int nh) {
  const int direction = colour / 2, parity = colour % 2;
  const Direction d = kDirections[direction];
  // The spring at (x, y) exists when both ends are in the grid.
  const int lo[2] = {d.dx < 0 ? -d.dx : 0, d.dy < 0 ? -d.dy : 0};
  const int hi[2] = {nw - (d.dx > 0 ? d.dx : 0), nh - (d.dy > 0 ? d.dy : 0)};
  // The colour's parity is on x for the horizontal directions, on y for all others.
  const int along = (direction == DIR_RIGHT || direction == DIR_RIGHT2) ? 0 : 1;
  const bool two_step = direction == DIR_RIGHT2 || direction == DIR_DOWN2;
  AxisSpan axes[2];
  for (int a = 0; a < 2; ++a) {
    AxisSpan s{lo[a], 0, 30, 0};
    if (a == along) {
      s = two_step ? AxisSpan{2 * parity, 4, 1, 0} : AxisSpan{lo[a] + ((lo[a] + parity) & 1), 2, 0, 0};
    }
    while (s.at(s.count) < hi[a]) ++s.count;  // coordinates increase with i
    axes[a] = s;
  }
  return {axes[0], axes[1]};
}

}  // namespace clothsim

// Colours of springs for parallel constraint passes: the springs of one colour share no
// particle, so a pass may update all of them at once without races (the mesh counterpart of
// the grid's fixed twelve colours, spring_grid.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace clothsim {

// Colours the springs so that no two springs of one colour share a particle: each spring gets the
// smallest colour not used by a spring already coloured at either end, in the given order. Deterministic.
// At most 2 * (max particle degree) - 1 colours. Throws std::invalid_argument for an index >= particle_count.
std::vector<uint32_t> greedy_colouring(const std::vector<std::array<uint32_t, 2>>& springs, size_t particle_count);

// True when no two springs of one colour share a particle (for tests and a load-time assert).
// False too when the sizes differ or an index is out of range.
bool colouring_is_valid(const std::vector<std::array<uint32_t, 2>>& springs, const std::vector<uint32_t>& colour,
                        size_t particle_count);

// The number of colours used (1 + the largest), 0 for no springs.
uint32_t colour_count(const std::vector<uint32_t>& colour);

}  // namespace clothsim

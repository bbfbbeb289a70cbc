// Building blocks shared by the texgen sources (not part of the tool's interface).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "texgen.hpp"

namespace clothsim::texgen::detail {

uint32_t hash(uint32_t x);
uint32_t hash(int a, int b, uint32_t seed);
float unit(uint32_t h);  // a hash mapped to [0, 1)

// Value noise on an integer lattice that repeats every period_x, period_y cells.
float value_noise(float x, float y, int period_x, int period_y, uint32_t seed);
// Sum of octaves of value_noise over (u, v) in [0, 1)^2, periodic in both; result in [0, 1].
float fbm(float u, float v, int base_period, int octaves, uint32_t seed);

// Mean of f over 4x4 sub-samples of each pixel of a size x size tile; f takes (u, v) in [0, 1).
std::vector<glm::vec3> supersample(int size, const std::function<glm::vec3(float, float)>& f);
// Rounds [0, 1] values to 8 bits, keeping the first `channels` components.
Image quantize(int size, const std::vector<glm::vec3>& colors, int channels);

// What the plain weave shows at (u, v): the top thread, or the gap between threads.
struct WeaveSample {
  float height;   // 0 in a gap, up to 1 on top of a crossing
  bool warp;      // the top thread runs along v (warp) rather than along u (weft)
  bool gap;
  float across;   // -1..1 across the top thread
  float along;    // position along it, in thread spacings
  int index;      // which thread of its direction
};
WeaveSample weave_at(float u, float v);

}  // namespace clothsim::texgen::detail

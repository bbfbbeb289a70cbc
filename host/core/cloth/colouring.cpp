// Greedy colouring with one 64-bit mask of used colours per particle: a spring's colour is the
// lowest zero bit of its two ends' masks, O(1) per spring. A spring whose ends have used all
// 64 colours of the current block is deferred to the next block (colours 64..127, fresh masks):
// no spring of an earlier block can take a colour of a later one, so the result is exactly the
// one-spring-at-a-time greedy in the given order, and a block costs one pass over its springs.
#include "cloth/colouring.hpp"

#include <algorithm>
#include <bit>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace clothsim {

std::vector<uint32_t> greedy_colouring(const std::vector<std::array<uint32_t, 2>>& springs, size_t particle_count) {
  for (const auto& [a, b] : springs)
    if (a >= particle_count || b >= particle_count)
      throw std::invalid_argument("greedy_colouring: a spring refers to a particle beyond the particle count");
  std::vector<uint32_t> colour(springs.size(), 0);
  std::vector<uint32_t> pending(springs.size()), deferred;
  std::iota(pending.begin(), pending.end(), 0u);
  std::vector<uint64_t> used(particle_count);
  for (uint32_t base = 0; !pending.empty(); base += 64) {
    std::fill(used.begin(), used.end(), 0);
    deferred.clear();
    for (uint32_t i : pending) {
      const auto [a, b] = springs[i];
      const uint64_t busy = used[a] | used[b];
      if (busy == ~uint64_t(0)) {
        deferred.push_back(i);
        continue;
      }
      const int c = std::countr_one(busy);
      colour[i] = base + uint32_t(c);
      used[a] |= uint64_t(1) << c;
      used[b] |= uint64_t(1) << c;
    }
    std::swap(pending, deferred);
  }
  return colour;
}

bool colouring_is_valid(const std::vector<std::array<uint32_t, 2>>& springs, const std::vector<uint32_t>& colour,
                        size_t particle_count) {
  if (colour.size() != springs.size()) return false;
  // Every (particle, colour) pair once: sort them and look for neighbours that are equal.
  std::vector<uint64_t> ends;
  ends.reserve(springs.size() * 2);
  for (size_t i = 0; i < springs.size(); ++i) {
    const auto [a, b] = springs[i];
    if (a >= particle_count || b >= particle_count) return false;
    ends.push_back((uint64_t(a) << 32) | colour[i]);
    if (b != a) ends.push_back((uint64_t(b) << 32) | colour[i]);
  }
  std::sort(ends.begin(), ends.end());
  return std::adjacent_find(ends.begin(), ends.end()) == ends.end();
}

uint32_t colour_count(const std::vector<uint32_t>& colour) {
  return colour.empty() ? 0 : *std::max_element(colour.begin(), colour.end()) + 1;
}

}  // namespace clothsim

// What the self-intersection tests share (test_intersections.cpp, test_exact_predicates.cpp):
// a triangle mesh counted by count_self_intersections, and a fixed-seed generator.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/vec3.hpp>

#include "analysis/intersections.hpp"

namespace clothsim::test {

using Tris = std::vector<std::array<uint32_t, 3>>;
using Points = std::vector<glm::dvec3>;

struct Mesh {
  Points pos;
  Tris tri;
  // Appends `other` as another part (its indices shifted).
  void append(const Mesh& other) {
    const auto base = uint32_t(pos.size());
    pos.insert(pos.end(), other.pos.begin(), other.pos.end());
    for (auto t : other.tri) tri.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  size_t count() const { return count_self_intersections(tri, pos); }
};

// Deterministic doubles in [0, 1) from a fixed-seed mt19937 (no std:: distribution).
struct Rng {
  std::mt19937 g;
  explicit Rng(uint32_t seed) : g(seed) {}
  double uniform() { return double(g()) * 0x1p-32; }
  double in(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int below(int n) { return int(g() % uint32_t(n)); }
};

}  // namespace clothsim::test

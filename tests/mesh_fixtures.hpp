// What the mesh-cloth tests share (test_mesh_import.cpp, test_mesh_springs.cpp): a temporary
// directory for mesh files, and the CS184 grid as a mesh with its spring sets.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <glm/vec3.hpp>

#include "cloth/mesh_springs.hpp"

namespace clothsim::test {


// A fresh directory under the system's temp directory, removed afterwards.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    static int counter = 0;
    path = std::filesystem::temp_directory_path() / fmt::format("clothsim_mesh_test_{}_{}", getpid(), counter++);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
    return path / name;
  }
};

using Pairs = std::vector<std::array<uint32_t, 2>>;
using PairSet = std::set<std::pair<uint32_t, uint32_t>>;

inline PairSet unordered(const Pairs& pairs) {
  PairSet out;
  for (auto [a, b] : pairs) out.insert({std::min(a, b), std::max(a, b)});
  return out;
}

// The CS184 grid's positions (horizontal, as host/core/cloth/cloth.cpp makes them), its quads
// (A B D C per cell, row major) and its spring sets.
struct Grid {
  int nw, nh;
  std::vector<glm::dvec3> positions;
  std::vector<std::vector<uint32_t>> faces;
  PairSet structural, shearing, bending;

  Grid(int nw_, int nh_, double width = 1.0, double height = 1.0) : nw(nw_), nh(nh_) {
    const double sx = width / (nw - 1), sy = height / (nh - 1);
    auto at = [&](int x, int y) { return uint32_t(y * nw + x); };
    for (int y = 0; y < nh; ++y)
      for (int x = 0; x < nw; ++x) positions.push_back({x * sx, 1.0, y * sy});
    for (int y = 0; y + 1 < nh; ++y)
      for (int x = 0; x + 1 < nw; ++x) faces.push_back({at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1)});
    for (int y = 0; y < nh; ++y)
      for (int x = 0; x < nw; ++x) {
        if (x + 1 < nw) structural.insert({at(x, y), at(x + 1, y)});
        if (y + 1 < nh) structural.insert({at(x, y), at(x, y + 1)});
        if (x + 1 < nw && y + 1 < nh) shearing.insert({at(x, y), at(x + 1, y + 1)}), shearing.insert({at(x + 1, y), at(x, y + 1)});
        if (x + 2 < nw) bending.insert({at(x, y), at(x + 2, y)});
        if (y + 2 < nh) bending.insert({at(x, y), at(x, y + 2)});
      }
  }

  // As scripts/make-mesh grid writes it; faces in the order given (default: row major).
  std::string obj(std::vector<size_t> order = {}) const {
    if (order.empty()) order.resize(faces.size()), std::iota(order.begin(), order.end(), size_t(0));
    std::string s = "# a CS184 grid\n";
    for (const auto& p : positions) s += fmt::format("v {:.17g} {:.17g} {:.17g}\n", p.x, p.y, p.z);
    for (int y = 0; y < nh; ++y)
      for (int x = 0; x < nw; ++x) s += fmt::format("vt {:.17g} {:.17g}\n", double(x) / (nw - 1), double(y) / (nh - 1));
    for (size_t f : order) {
      s += "f";
      for (uint32_t i : faces[f]) s += fmt::format(" {}/{}", i + 1, i + 1);
      s += "\n";
    }
    return s;
  }
};

// Every spring of a mesh: structural, then shearing, then bending.
inline Pairs all_springs(const MeshSprings& s) {
  Pairs out = s.structural;
  out.insert(out.end(), s.shearing.begin(), s.shearing.end());
  out.insert(out.end(), s.bending.begin(), s.bending.end());
  return out;
}

}  // namespace clothsim::test

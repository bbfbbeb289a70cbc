// cloth.seams as springs (docs/model.md, "Sewing"): each pair of sewn vertices gets a spring of
// type Seam whose rest length starts at the pair's distance (the solvers shrink it to zero at
// simulation.sewing_speed), coloured like any spring so the colour sweeps never race, and the
// welds that keep self-collision from pushing a sewn pair apart.
#include "cloth/cloth.hpp"

#include <algorithm>
#include <numeric>
#include <set>

#include <fmt/format.h>
#include <glm/geometric.hpp>

namespace clothsim {

namespace {

// One side of a seam as particle indices, in order: `vertices` (0-based in the cloth), a grid's
// `edge` (ascending grid index) or the vertices inside `box` (along its longest side).
std::vector<uint32_t> seam_side(const Scene& scene, const ClothModel& m, const ClothPart& part,
                                const std::vector<int>& vertices, const std::string& edge,
                                const std::optional<BoxParams>& box, const std::string& key) {
  std::vector<uint32_t> out;
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (vertices[v] < 0 || uint32_t(vertices[v]) >= part.count)
      throw SceneError(fmt::format("{}: {}[{}]: vertex {} is out of range: the cloth has {} vertices (0 to {})",
                                   scene.source, key, v, vertices[v], part.count, part.count - 1));
    out.push_back(part.first + uint32_t(vertices[v]));
  }
  if (!edge.empty()) {  // the loader allowed an edge only on a grid
    const uint32_t nw = uint32_t(part.nw), nh = uint32_t(part.nh);
    const bool column = edge[0] == 'x', last = edge.ends_with("max");
    const uint32_t count = column ? nh : nw;
    for (uint32_t k = 0; k < count; ++k) {
      const uint32_t x = column ? (last ? nw - 1 : 0) : k, y = column ? k : (last ? nh - 1 : 0);
      out.push_back(part.first + y * nw + x);
    }
  }
  if (box) {
    const glm::dvec3 size = box->max - box->min;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    for (uint32_t i = part.first; i < part.first + part.count; ++i)
      if (box->contains(m.initial[i])) out.push_back(i);
    std::stable_sort(out.begin(), out.end(),
                     [&](uint32_t a, uint32_t b) { return m.initial[a][axis] < m.initial[b][axis]; });
  }
  return out;
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

PartSprings sew_seams(const Scene& scene, ClothModel& m) {
  PartSprings out;
  const auto cloths = scene.cloths();
  const bool array = cloths.size() > 1;
  std::set<std::pair<uint32_t, uint32_t>> pairs;  // each pair once, (lower, higher)
  for (size_t c = 0; c < cloths.size(); ++c)
    for (size_t k = 0; k < cloths[c]->seams.size(); ++k) {
      const SeamParams& seam = cloths[c]->seams[k];
      const std::string key = fmt::format("{}.seams[{}]", array ? fmt::format("cloth[{}]", c) : "cloth", k);
      const size_t other = seam.to_cloth < 0 ? c : size_t(seam.to_cloth);
      const auto a = seam_side(scene, m, m.parts[c], seam.vertices, seam.edge, seam.box,
                               key + (seam.edge.empty() ? ".vertices" : ".edge"));
      const auto b = seam_side(scene, m, m.parts[other], seam.to_vertices, seam.to_edge, seam.to_box,
                               key + (seam.to_edge.empty() ? ".to_vertices" : ".to_edge"));
      if (a.size() != b.size() || a.empty())
        throw SceneError(fmt::format("{}: {}: the sides have {} and {} vertices: expected as many on each, at least "
                                     "one (the k-th of one side is sewn to the k-th of the other)",
                                     scene.source, key, a.size(), b.size()));
      for (size_t v = 0; v < a.size(); ++v) {
        if (a[v] == b[v])
          throw SceneError(fmt::format("{}: {}: pair {} sews vertex {} to itself: expected two different vertices",
                                       scene.source, key, v, a[v] - m.parts[c].first));
        pairs.insert({std::min(a[v], b[v]), std::max(a[v], b[v])});
      }
    }
  if (pairs.empty()) return out;
  // Greedy colouring in pair order: each spring takes the least colour neither end has yet.
  std::vector<std::vector<uint32_t>> used(size_t(m.count()));
  std::vector<uint32_t> parent(size_t(m.count()));
  std::iota(parent.begin(), parent.end(), 0u);
  for (const auto& pair : pairs) {
    const uint32_t i = pair.first, j = pair.second;  // named: C++17 lambdas cannot capture structured bindings
    uint32_t colour = 0;
    auto taken = [&](uint32_t col) {
      return std::count(used[i].begin(), used[i].end(), col) + std::count(used[j].begin(), used[j].end(), col) > 0;
    };
    while (taken(colour)) ++colour;
    used[i].push_back(colour);
    used[j].push_back(colour);
    out.springs.push_back({.i = i, .j = j, .rest = glm::distance(m.initial[i], m.initial[j]),
                           .type = SpringType::Seam, .material = m.material[i]});
    out.colour.push_back(colour);
    const uint32_t ri = find_root(parent, i), rj = find_root(parent, j);
    parent[std::max(ri, rj)] = std::min(ri, rj);  // the root stays the least index
  }
  m.weld.resize(size_t(m.count()));
  for (uint32_t i = 0; i < m.weld.size(); ++i) m.weld[i] = find_root(parent, i);
  return out;
}

}  // namespace clothsim

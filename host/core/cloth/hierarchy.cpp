#include "cloth/hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <glm/geometric.hpp>

namespace clothsim {

namespace {

using Graph = std::vector<std::vector<uint32_t>>;  // ascending neighbour lists, no duplicates

void sort_unique(Graph& g) {
  for (auto& n : g) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
}

// The particles joined by springs (any cloth, enabled or not: the graph is the rest shape's, not
// the run's): every spring and hinge for the colouring of a sweep (`all`), else the structural and
// shearing ones, which coarsen. Seams do not: their start length is no rest shape, so each
// panel coarsens on its own and the fine sweep joins them.
Graph spring_graph(const ClothModel& m, bool all) {
  Graph g(m.count());
  for (const Spring& s : m.springs) {
    if (!all && (s.type == SpringType::Bending || s.type == SpringType::Seam)) continue;
    g[s.i].push_back(s.j);
    g[s.j].push_back(s.i);
  }
  // A stencil's particles read each other in the sweep: no two of one colour.
  for (uint32_t i = 0; all && i + 1 < m.hinge_start.size(); ++i) {
    for (uint32_t h = m.hinge_start[i]; h < m.hinge_start[i + 1]; ++h)
      for (uint32_t o : m.hinges[h].other) g[i].push_back(o);
    for (uint32_t e = m.bend_start[i]; e < m.bend_start[i + 1]; ++e)
      if (m.bend[e].other != i) g[i].push_back(m.bend[e].other);
  }
  sort_unique(g);
  return g;
}

// The order in which the hierarchy visits a level's vertices (their particles `particles`): by
// rest position, not by index, so the same cloth numbered otherwise (a grid, or the same grid as
// a mesh in another vertex order) gets the same coarse vertices and colours, and one sweep the
// same answer (issue 43, item 2). Positions are compared quantised to a quarter of the shortest
// spring (a grid's jitter of at most 5 % of its spacing does not reorder a row), z, then y, then
// x: a grid's own order, row by row (so a grid's hierarchy is what index order gave it); exact
// positions, then the index, break ties. `quantum` is ordering_quantum(m), found once per build.
double ordering_quantum(const ClothModel& m) {
  double shortest = 0;
  for (const Spring& s : m.springs)
    if (s.type != SpringType::Seam && s.rest > 0 && (shortest == 0 || s.rest < shortest)) shortest = s.rest;
  return shortest > 0 ? 0.25 * shortest : 1.0;
}

std::vector<uint32_t> canonical_order(const ClothModel& m, double quantum, const std::vector<uint32_t>& particles) {
  using Key = std::tuple<long long, long long, long long, double, double, double, uint32_t>;
  std::vector<Key> keys(particles.size());  // each once, not in every comparison
  for (uint32_t v = 0; v < keys.size(); ++v) {
    const glm::dvec3& p = m.initial[particles[v]];
    keys[v] = {std::llround(p.z / quantum), std::llround(p.y / quantum), std::llround(p.x / quantum), p.z, p.y, p.x, v};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<uint32_t> order(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) order[k] = std::get<6>(keys[k]);
  return order;
}

// Greedy colouring in the order `visit`: each vertex takes the smallest colour none of its
// coloured neighbours has. Returns the vertices grouped by colour (ascending within one) and the
// starts. `start` gets order.size() before and after each colour.
void colour_vertices(const Graph& g, const std::vector<uint32_t>& visit, uint32_t base, std::vector<uint32_t>& order,
                     std::vector<uint32_t>& start) {
  const size_t n = g.size();
  std::vector<int> colour(n, -1);
  int colours = 0;
  std::vector<char> used;
  for (uint32_t v : visit) {
    used.assign(size_t(colours) + 1, 0);
    for (uint32_t u : g[v])
      if (colour[u] >= 0) used[size_t(colour[u])] = 1;
    int c = 0;
    while (used[size_t(c)]) ++c;
    colour[v] = c;
    colours = std::max(colours, c + 1);
  }
  start.assign(1, uint32_t(order.size()));
  for (int c = 0; c < colours; ++c) {
    for (size_t v = 0; v < n; ++v)
      if (colour[v] == c) order.push_back(base + uint32_t(v));
    start.push_back(uint32_t(order.size()));
  }
}

}  // namespace

Hierarchy build_hierarchy(const ClothModel& m, const std::vector<double>& ks) {
  Hierarchy h;
  h.ks = ks;
  // The current level: its vertices' particles and their graph (structural and shearing springs
  // on the cloth itself, the coarse springs further down).
  Graph graph = spring_graph(m, false);
  std::vector<uint32_t> particles(size_t(m.count()));
  for (uint32_t i = 0; i < particles.size(); ++i) particles[i] = i;
  const double quantum = ordering_quantum(m);
  colour_vertices(spring_graph(m, true), canonical_order(m, quantum, particles), 0, h.fine_order, h.fine_colour_start);
  h.fine_colour.assign(particles.size(), 0u);
  for (uint32_t k = 0; k + 1 < h.fine_colour_start.size(); ++k)
    for (uint32_t e = h.fine_colour_start[k]; e < h.fine_colour_start[k + 1]; ++e) h.fine_colour[h.fine_order[e]] = k;
  uint32_t finer_base = 0;  // global index of the current level's vertex 0 (unused for the cloth)
  bool cloth_level = true;
  h.fine_parent_start.push_back(0);
  h.parent_start.push_back(0);

  while (particles.size() > kCoarsestVertices && h.levels.size() < 16) {
    const size_t n = particles.size();
    // A maximal independent set, pinned particles first so a pin is a coarse vertex (a coarse
    // correction then holds still where the cloth is held), then in the canonical order.
    std::vector<char> taken(n, 0);
    std::vector<int64_t> coarse_of(n, -1);
    std::vector<uint32_t> coarse;
    auto make_coarse = [&](uint32_t v) {
      coarse_of[v] = int64_t(coarse.size());
      coarse.push_back(v);
    };
    auto take = [&](uint32_t v) {
      if (taken[v]) return;
      make_coarse(v);
      taken[v] = 1;
      for (uint32_t u : graph[v]) taken[u] = 1;
    };
    const std::vector<uint32_t> visit = canonical_order(m, quantum, particles);
    for (uint32_t v : visit)
      if (m.pinned[particles[v]]) take(v);
    for (uint32_t v : visit) take(v);
    // Every spring between two fine vertices must have a coarse parent at both ends (Ruge and
    // Stüben's second pass): else the coarse graph, which joins vertices that share a child,
    // has a crack there, and the coarse cloth on one side of it floats free of the other, pins
    // included. An MIS leaves such cracks wherever two coarse vertices land three springs apart:
    // a grid whose pinned row has the other parity (a 20-row strip pinned along row 19: rows
    // 16 and 19 coarse, 17 and 18 not, so the coarse strip hung from nothing and its
    // correction threw it off at frame 2), and anywhere on a mesh. The later end of such a
    // spring becomes coarse too, so the set is no longer independent there.
    auto shares_parent = [&](uint32_t a, uint32_t b) {
      for (uint32_t p : graph[a])
        if (coarse_of[p] >= 0 && std::binary_search(graph[b].begin(), graph[b].end(), p)) return true;
      return false;
    };
    for (uint32_t v : visit) {
      if (coarse_of[v] >= 0) continue;
      for (uint32_t u : graph[v])
        if (coarse_of[u] < 0 && !shares_parent(v, u)) make_coarse(u);
    }
    // No extrapolation: a vertex with one coarse neighbour would take a copy of that parent's
    // correction. On a grid of even size the MIS leaves the last row and column out, and each
    // level's overhang beyond its edge doubles (2^l - 1 cells at level l), copied whole from
    // the edge: a coarse correction that turns or bends there strained the overhang, and in
    // float a 512² flag falling free tore at its far corner (docs/solvers.md, "Even grids").
    // Such a vertex becomes coarse too (an odd grid has none).
    for (uint32_t v : visit) {
      if (coarse_of[v] >= 0) continue;
      size_t coarse_neighbours = 0;
      for (uint32_t u : graph[v]) coarse_neighbours += coarse_of[u] >= 0 ? 1 : 0;
      if (coarse_neighbours == 1) make_coarse(v);
    }
    // Not worth a level: the graph hardly coarsens (a cloud of loose particles).
    if (coarse.size() * 5 > n * 4) break;
    // With the MIS in the canonical order the coarse vertices are not ascending: number them in
    // index order so levels are laid out like the cloth.
    std::sort(coarse.begin(), coarse.end());
    for (size_t k = 0; k < coarse.size(); ++k) coarse_of[coarse[k]] = int64_t(k);

    const uint32_t base = h.coarse_count();
    HierarchyLevel level;
    level.first = base;
    level.count = uint32_t(coarse.size());
    // Parents of every vertex of the current level: itself if coarse, else its coarse neighbours.
    std::vector<std::vector<uint32_t>> parents(n);
    for (uint32_t v = 0; v < n; ++v) {
      if (coarse_of[v] >= 0) parents[v].push_back(uint32_t(coarse_of[v]));
      else
        for (uint32_t u : graph[v])
          if (coarse_of[u] >= 0) parents[v].push_back(uint32_t(coarse_of[u]));
    }
    // The coarse graph: two coarse vertices are joined when they share a child.
    Graph coarse_graph(coarse.size());
    for (uint32_t v = 0; v < n; ++v)
      for (uint32_t a : parents[v])
        for (uint32_t b : parents[v])
          if (a != b) coarse_graph[a].push_back(b);
    // and when they are neighbours themselves (the second pass above makes such pairs).
    for (uint32_t v = 0; v < n; ++v)
      for (uint32_t u : graph[v])
        if (coarse_of[v] >= 0 && coarse_of[u] >= 0) coarse_graph[uint32_t(coarse_of[v])].push_back(uint32_t(coarse_of[u]));
    sort_unique(coarse_graph);

    // Prolongation of the current level (the cloth's particles, or the previous coarse level).
    for (uint32_t v = 0; v < n; ++v) {
      const double w = 1.0 / double(parents[v].size());
      for (uint32_t a : parents[v]) {
        if (cloth_level) {
          h.fine_parent.push_back(base + a);
          h.fine_parent_weight.push_back(w);
        } else {
          h.parent.push_back(base + a);
          h.parent_weight.push_back(w);
        }
      }
      if (cloth_level) h.fine_parent_start.push_back(uint32_t(h.fine_parent.size()));
      else h.parent_start.push_back(uint32_t(h.parent.size()));
    }
    // The coarse vertices: their particles, children (the transpose) and springs.
    std::vector<std::vector<std::pair<uint32_t, double>>> children(coarse.size());
    for (uint32_t v = 0; v < n; ++v)
      for (uint32_t a : parents[v])
        children[a].push_back({(cloth_level ? 0 : uint32_t(m.count()) + finer_base) + v, 1.0 / double(parents[v].size())});
    for (size_t a = 0; a < coarse.size(); ++a) {
      const uint32_t p = particles[coarse[a]];
      h.particle.push_back(p);
      if (h.child_start.empty()) h.child_start.push_back(0);
      for (auto& [c, w] : children[a]) {
        h.child.push_back(c);
        h.child_weight.push_back(w);
      }
      h.child_start.push_back(uint32_t(h.child.size()));
      if (h.spring_start.empty()) h.spring_start.push_back(0);
      const double k = kCoarseStiffness * ks[m.material[p]];
      for (uint32_t b : coarse_graph[a]) {
        h.spring_other.push_back(base + b);
        h.spring_rest.push_back(glm::distance(m.initial[p], m.initial[particles[coarse[b]]]));
        h.spring_k.push_back(k);
      }
      h.spring_start.push_back(uint32_t(h.spring_other.size()));
    }
    std::vector<uint32_t> coarse_particles(coarse.size());
    for (size_t a = 0; a < coarse.size(); ++a) coarse_particles[a] = particles[coarse[a]];
    colour_vertices(coarse_graph, canonical_order(m, quantum, coarse_particles), base, h.order, level.colour_start);
    h.levels.push_back(level);

    std::vector<uint32_t> next(coarse.size());
    for (size_t a = 0; a < coarse.size(); ++a) next[a] = particles[coarse[a]];
    particles = std::move(next);
    graph = std::move(coarse_graph);
    finer_base = base;
    cloth_level = false;
  }
  // The coarsest level has no parents; every coarse vertex has a (possibly empty) parent list.
  while (h.parent_start.size() < size_t(h.coarse_count()) + 1) h.parent_start.push_back(uint32_t(h.parent.size()));
  if (h.levels.empty()) {
    // No coarse level (a small cloth): every particle without parents; the sweep alone solves.
    h.fine_parent_start.assign(size_t(m.count()) + 1, 0);
    h.child_start = {0};
    h.spring_start = {0};
  }
  return h;
}

}  // namespace clothsim

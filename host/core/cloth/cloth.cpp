// What every cloth builder shares: the model's derived lists (springs sorted by colour, the
// force gather, the triangles around each particle) and the masses.
#include "cloth/cloth.hpp"

#include "io/host_memory.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

namespace clothsim {

double vertical_offset(uint32_t i, double amplitude, uint32_t seed) {
  // splitmix64 finaliser: a well-mixed, portable hash of the index (and the seed, in the high
  // word, so seed 0 is the classic draw).
  uint64_t z = uint64_t(i) + (uint64_t(seed) << 32) + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  double u = double(z >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
  return (2.0 * u - 1.0) * amplitude;
}

double jitter_amplitude(double spacing) {
  // The classic +-1 mm, but never more than 5 % of the spacing: on a fine cloth 1 mm would be
  // a crumple baked into the rest lengths. At the classic spacing (1/49 m) 5 % is 1.02 mm, so
  // the classic scenes keep exactly 1e-3.
  return std::min(1e-3, 0.05 * spacing);
}

double particle_mass(const ClothParams& p) {
  return p.width * p.height * p.areal_density() / (double(p.num_width_points) * double(p.num_height_points));
}

std::vector<double> particle_masses(const Scene& scene, const ClothModel& m) {
  const auto cloths = scene.cloths();
  std::vector<double> mass(m.count());
  for (size_t k = 0; k < m.parts.size(); ++k) {
    const ClothPart& part = m.parts[k];
    const ClothParams& p = *cloths.at(k);
    // A grid keeps the CS184 formula exactly (its particles all weigh the same, to the bit).
    const bool even = part.nw > 0 && !p.material;
    const double grid_mass = even ? particle_mass(p) : 0.0;
    for (uint32_t i = part.first; i < part.first + part.count; ++i)
      mass[i] = even ? grid_mass : m.area[i] * p.areal_density();
  }
  return mass;
}

int ClothModel::springs_of(SpringType type) const {
  return int(std::count_if(springs.begin(), springs.end(), [&](const Spring& s) { return s.type == type; }));
}

namespace {

// Springs of all parts sorted into colours: by type, then by the colour within the type (the
// same colour of two parts merges into one: their particles are disjoint). Returns, for each
// spring of each part in order, its index in the sorted list.
std::vector<uint32_t> sort_by_colour(ClothModel& m, const std::vector<PartSprings>& parts) {
  uint32_t per_type[kSpringTypes] = {0, 0, 0, 0};
  for (auto& p : parts)
    for (size_t s = 0; s < p.springs.size(); ++s) {
      uint32_t& n = per_type[int(p.springs[s].type)];
      n = std::max(n, p.colour[s] + 1);
    }
  uint32_t first[kSpringTypes] = {0, 0, 0, 0};
  for (int t = 1; t < kSpringTypes; ++t) first[t] = first[t - 1] + per_type[t - 1];
  const uint32_t colours = first[kSpringTypes - 1] + per_type[kSpringTypes - 1];
  std::vector<uint32_t> size(colours, 0);
  std::vector<uint32_t> global;  // global colour of each spring, parts in order
  for (auto& p : parts)
    for (size_t s = 0; s < p.springs.size(); ++s) {
      global.push_back(first[int(p.springs[s].type)] + p.colour[s]);
      ++size[global.back()];
    }
  m.colour_start.assign(colours + 1, 0);
  for (uint32_t c = 0; c < colours; ++c) m.colour_start[c + 1] = m.colour_start[c] + size[c];
  // A stable counting sort: within a colour, springs keep their builder's order.
  std::vector<uint32_t> cursor(m.colour_start.begin(), m.colour_start.end() - 1);
  std::vector<uint32_t> where(global.size());
  m.springs.resize(global.size());
  size_t k = 0;
  for (auto& p : parts)
    for (const Spring& s : p.springs) {
      where[k] = cursor[global[k]]++;
      m.springs[where[k]] = s;
      ++k;
    }
  return where;
}

}  // namespace

void finish_model(ClothModel& m, const std::vector<PartSprings>& parts) {
  const std::vector<uint32_t> where = sort_by_colour(m, parts);
  const uint32_t n = uint32_t(m.count());
  // The force gather: a builder's own order where it gives one (the grid's kGatherOrder, which
  // keeps the classic sums to the bit), else every spring at the particle in sorted order.
  m.gather_start.assign(n + 1, 0);
  std::vector<std::vector<uint32_t>> lists(n);
  size_t offset = 0;
  for (size_t k = 0; k < parts.size(); ++k) {
    if (k < m.parts.size() && !parts[k].gather.empty()) {
      const ClothPart& part = m.parts[k];
      uint32_t i = part.first;
      for (uint32_t s : parts[k].gather) {
        if (s == kEndOfList) { ++i; continue; }
        lists[i].push_back(where[offset + s]);
      }
    }
    offset += parts[k].springs.size();
  }
  std::vector<uint8_t> given(n, 0);
  for (size_t k = 0; k < m.parts.size(); ++k)
    if (!parts[k].gather.empty())
      for (uint32_t i = m.parts[k].first; i < m.parts[k].first + m.parts[k].count; ++i) given[i] = 1;
  // A builder's order has no seams (they join parts): they follow it, in sorted order.
  for (uint32_t s = 0; s < m.springs.size(); ++s)
    for (uint32_t end : {m.springs[s].i, m.springs[s].j})
      if (!given[end] || m.springs[s].type == SpringType::Seam) lists[end].push_back(s);
  for (uint32_t i = 0; i < n; ++i) {
    m.gather_start[i + 1] = m.gather_start[i] + uint32_t(lists[i].size());
    m.gather.insert(m.gather.end(), lists[i].begin(), lists[i].end());
  }
  // The triangles around each particle, ascending: on a grid that is the classic order of the
  // cells (x-1..x, y-1..y), each (A, C, B) then (B, C, D).
  m.corner_start.assign(n + 1, 0);
  for (auto& t : m.triangles)
    for (uint32_t v : t) ++m.corner_start[v + 1];
  for (uint32_t i = 0; i < n; ++i) m.corner_start[i + 1] += m.corner_start[i];
  m.corner_triangles.resize(m.corner_start[n]);
  std::vector<uint32_t> cursor(m.corner_start.begin(), m.corner_start.end() - 1);
  for (uint32_t t = 0; t < m.triangles.size(); ++t)
    for (uint32_t v : m.triangles[t]) m.corner_triangles[cursor[v]++] = t;
}

std::string describe_cloth(const ClothModel& m) {
  if (m.is_grid()) return fmt::format("{}x{} cloth", m.nw, m.nh);
  if (m.parts.size() == 1)
    return fmt::format("mesh cloth of {} particles, {} springs, {} colours", m.count(), m.springs.size(), m.colours());
  return fmt::format("{} cloths, {} particles, {} springs, {} colours", m.parts.size(), m.count(), m.springs.size(),
                     m.colours());
}

static ClothModel build_cloth_model(const Scene& scene);

// Self-collision compares each particle with those in the 27 hash cells of 2 x thickness around
// it: on a flat cloth about 36 (thickness / spacing)^2 of them. A thickness many times the
// spacing makes that thousands (a substep of minutes, with no sign of why): refused, naming the
// cost and the largest thickness that keeps it in bounds. Real scenes stay below 1 x spacing.
void check_self_collision_cost(const Scene& scene, const ClothModel& m) {
  if (!scene.simulation.self_collision || m.count() == 0) return;
  std::vector<double> rest;
  for (const Spring& s : m.springs)
    if (s.type == SpringType::Structural && s.rest > 0) rest.push_back(s.rest);
  if (rest.empty()) return;
  std::nth_element(rest.begin(), rest.begin() + long(rest.size() / 2), rest.end());
  const double spacing = rest[rest.size() / 2];  // the median: one odd edge does not decide
  const auto cloths = scene.cloths();
  const ClothParams* thickest = cloths[0];
  for (const ClothParams* c : cloths)
    if (c->thickness > thickest->thickness) thickest = c;
  const double ratio = thickest->thickness / spacing;
  const double neighbours = std::min(double(m.count()), 36.0 * ratio * ratio);
  if (neighbours <= kMaxSelfCollisionNeighbours) return;
  const double largest = spacing * std::sqrt(kMaxSelfCollisionNeighbours / 36.0);
  std::string key = "cloth";
  for (size_t k = 0; k < cloths.size(); ++k)
    if (cloths[k] == thickest && cloths.size() > 1) key = fmt::format("cloth[{}]", k);
  throw SceneError(fmt::format(
      "{}: {}.thickness: {:g} m is {:.3g} x the particle spacing ({:.3g} m): self-collision would compare each particle "
      "with about {:.0f} others ({:.3g} pairs a substep); at most {:g} are accepted: expected a thickness of at most "
      "{:.3g} m, or simulation.self_collision false",
      scene.source, key, thickest->thickness, ratio, spacing, neighbours, neighbours * m.count(),
      kMaxSelfCollisionNeighbours, largest));
}

ClothModel build_cloth(const Scene& scene) {
  // The model's arrays for the grid cloths: positions, uv, masses, about 8 springs a particle.
  const uint64_t particles = uint64_t(scene.particle_count());
  const uint64_t bytes = particles * (sizeof(glm::dvec3) * 2 + sizeof(double) * 2 + 8 * sizeof(Spring) + 16);
  ClothModel m = allocating(fmt::format("the cloth model of {} particles", particles), bytes,
                            [&] { return build_cloth_model(scene); });
  return m;
}

static ClothModel build_cloth_model(const Scene& scene) {
  ClothModel m;
  std::vector<PartSprings> parts;
  const auto cloths = scene.cloths();
  long long total = 0;
  for (uint32_t k = 0; k < cloths.size(); ++k) {
    const ClothParams& p = *cloths[k];
    ClothPart part;
    part.first = uint32_t(m.count());
    part.first_triangle = uint32_t(m.triangles.size());
    if (p.is_mesh()) {
      part.mesh = p.mesh_path.string();
      parts.push_back(append_mesh(m, scene, p, k));
    } else {
      part.nw = p.num_width_points;
      part.nh = p.num_height_points;
      parts.push_back(append_grid(m, p, k, uint32_t(scene.simulation.seed)));
    }
    part.count = uint32_t(m.count()) - part.first;
    part.triangle_count = uint32_t(m.triangles.size()) - part.first_triangle;
    m.parts.push_back(part);
    total += part.count;
    if (total > kMaxParticles)
      throw SceneError(fmt::format("{}: cloth: the cloths have {} particles in all, more than the {} this build "
                                   "accepts", scene.source, total, kMaxParticles));
  }
  if (m.parts.size() == 1 && m.parts[0].nw > 0) {
    m.nw = m.parts[0].nw;
    m.nh = m.parts[0].nh;
  }
  PartSprings seams = sew_seams(scene, m);
  if (!seams.springs.empty()) parts.push_back(std::move(seams));
  finish_model(m, parts);
  add_fabric_terms(scene, m);
  m.mass = particle_masses(scene, m);
  return m;
}

}  // namespace clothsim

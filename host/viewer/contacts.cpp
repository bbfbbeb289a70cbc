#include "contacts.hpp"

#include <numeric>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "spatial_hash.hpp"

namespace clothsim {

int count_self_contacts(const std::vector<glm::vec4>& pos, float contact) {
  const size_t n = pos.size();
  SpatialHash h;
  h.table_size = hash_table_size(uint32_t(n));
  h.count.assign(h.table_size, 0);
  h.start.assign(h.table_size + 1, 0);
  h.entries.assign(n, 0);
  const float inv = 1.f / contact;
  auto cell = [&](const glm::vec4& p) {
    return glm::ivec3(cell_coord(p.x, inv), cell_coord(p.y, inv), cell_coord(p.z, inv));
  };
  std::vector<uint32_t> buckets(n), order(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::ivec3 c = cell(pos[i]);
    buckets[i] = hash_cell(c.x, c.y, c.z, h.table_size);
  }
  std::iota(order.begin(), order.end(), 0u);
  count_cells(buckets, h);
  scan_cells(h);
  fill_cells(buckets, order, h);
  int pairs = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::ivec3 c = cell(pos[i]);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 nc = c + glm::ivec3(dx, dy, dz);
          const uint32_t b = hash_cell(nc.x, nc.y, nc.z, h.table_size);
          for (uint32_t e = h.start[b]; e < h.start[b + 1]; ++e) {
            const uint32_t j = h.entries[e];
            // Each pair once (j > i), each j only in its own cell.
            if (j <= i || cell(pos[j]) != nc) continue;
            if (glm::length(glm::vec3(pos[i]) - glm::vec3(pos[j])) < contact) ++pairs;
          }
        }
  }
  return pairs;
}

}  // namespace clothsim

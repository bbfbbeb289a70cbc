// A hashed uniform grid built by counting sort, the layout the GPU builds too:
// count per bucket -> exclusive prefix sum -> scatter ids -> sort ids within each bucket.
// Each stage is a function named like the compute shader that mirrors it.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "../../../compute/spatial_hash.glsl"

namespace clothsim {

using shared::hash_cell;  // the bucket of integer cell (x, y, z), shared with the GLSL
using shared::hash_row;

struct SpatialHash {
  uint32_t table_size = 0;         // power of two >= particles, at least 4
  std::vector<uint32_t> count;     // particles per bucket
  std::vector<uint32_t> start;     // exclusive prefix sum of count, table_size + 1 entries
  std::vector<uint32_t> entries;   // particle ids in bucket order, ascending within a bucket
};

uint32_t hash_table_size(uint32_t particles);
// An empty table for `particles` particles (every vector sized once).
SpatialHash make_spatial_hash(uint32_t particles);

// Integer cell of a coordinate: floor(x * inv_cell), a multiplication so both sides round
// alike, clamped to +-CELL_LIMIT (NaN to -CELL_LIMIT) so the conversion is always defined.
// (shared::cell_axis, compute/spatial_hash.glsl).
template <class R> int32_t cell_coord(R x, R inv_cell) { return shared::cell_axis(x * inv_cell); }
template <class V, class R> glm::ivec3 cell_of(const V& p, R inv_cell) {
  return {cell_coord(p.x, inv_cell), cell_coord(p.y, inv_cell), cell_coord(p.z, inv_cell)};
}

// The stages, each mirrored by a compute shader of the same name. `buckets[i]` is particle
// i's bucket. `fill_order` is the order particles are scattered in (identity normally; tests
// shuffle it, as the GPU's atomics do, to show the result does not depend on it).
void count_cells(const std::vector<uint32_t>& buckets, SpatialHash& h);
void scan_cells(SpatialHash& h);
void fill_cells(const std::vector<uint32_t>& buckets, const std::vector<uint32_t>& fill_order, SpatialHash& h);
void sort_cells(SpatialHash& h);  // ascending ids within each bucket

// All four stages over positions (anything with .x .y .z), scattered in index order.
template <class V, class R> void build_spatial_hash(const std::vector<V>& pos, R inv_cell, SpatialHash& h) {
  std::vector<uint32_t> buckets(pos.size()), order(pos.size());
  for (size_t i = 0; i < pos.size(); ++i) {
    const glm::ivec3 c = cell_of(pos[i], inv_cell);
    buckets[i] = hash_cell(c.x, c.y, c.z, h.table_size);
    order[i] = uint32_t(i);
  }
  count_cells(buckets, h);
  scan_cells(h);
  fill_cells(buckets, order, h);
  sort_cells(h);
}

// Calls visit(j) for every particle j in the 27 cells around cell c, in the order the GPU
// visits them (dz, then dy, then dx from -1 to 1; ascending ids within a cell). A bucket
// holds every cell that hashes to it: only j really in the cell is visited, so each
// neighbour is visited once however the 27 cells collide in the table. i itself is visited.
template <class V, class R, class Visit>
void for_each_neighbour(const SpatialHash& h, const std::vector<V>& pos, R inv_cell, const glm::ivec3& c,
                        Visit&& visit) {
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const glm::ivec3 nc = c + glm::ivec3(dx, dy, dz);
        const uint32_t b = hash_cell(nc.x, nc.y, nc.z, h.table_size);
        for (uint32_t e = h.start[b]; e < h.start[b + 1]; ++e) {
          const uint32_t j = h.entries[e];
          if (cell_of(pos[j], inv_cell) == nc) visit(j);
        }
      }
}

}  // namespace clothsim

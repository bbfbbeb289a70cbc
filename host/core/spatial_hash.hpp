// A hashed uniform grid built by counting sort, the layout the GPU builds too:
// count per bucket -> exclusive prefix sum -> scatter ids -> sort ids within each bucket.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace clothsim {

struct SpatialHash {
  uint32_t table_size = 0;         // power of two >= particles, at least 4
  std::vector<uint32_t> count;     // particles per bucket
  std::vector<uint32_t> start;     // exclusive prefix sum of count, table_size + 1 entries
  std::vector<uint32_t> entries;   // particle ids in bucket order, ascending within a bucket
};

uint32_t hash_table_size(uint32_t particles);

// The bucket of integer cell (ix, iy, iz); same arithmetic as compute/spatial_hash.glsl
// (32-bit wrap-around products, xor, add, mask). Rows (iy, iz) are scattered by the products;
// along x consecutive cells get consecutive buckets, so the three cells of a row that a
// particle visits are three adjacent buckets: one contiguous run of entries (collide_self.comp
// reads them as one range; the table has at least 4 buckets, so the three are distinct).
inline uint32_t hash_row(int32_t iy, int32_t iz) { return (uint32_t(iy) * 19349663u) ^ (uint32_t(iz) * 83492791u); }
inline uint32_t hash_cell(int32_t ix, int32_t iy, int32_t iz, uint32_t table_size) {
  return (hash_row(iy, iz) + uint32_t(ix)) & (table_size - 1u);
}

// Integer cell of a coordinate: floor(x * inv_cell), a multiplication so both sides round alike.
template <class R> int32_t cell_coord(R x, R inv_cell) { return int32_t(std::floor(x * inv_cell)); }

// The stages, each mirrored by a compute shader of the same name. `buckets[i]` is particle
// i's bucket. `fill_order` is the order particles are scattered in (identity normally; tests
// shuffle it to show the result does not depend on it).
void count_cells(const std::vector<uint32_t>& buckets, SpatialHash& h);
void scan_cells(SpatialHash& h);
void fill_cells(const std::vector<uint32_t>& buckets, const std::vector<uint32_t>& fill_order, SpatialHash& h);

}  // namespace clothsim

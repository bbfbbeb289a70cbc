#include "spatial_hash.hpp"

#include <algorithm>

namespace clothsim {

uint32_t hash_table_size(uint32_t particles) {
  // A load factor up to 1: a larger table spends more on clearing, scanning and sorting
  // buckets than it saves on candidates from other cells (measured at 256^2 on llvmpipe).
  uint32_t size = 4;  // three adjacent buckets must be distinct (hash_cell)
  while (size < particles) size <<= 1;
  return size;
}

void count_cells(const std::vector<uint32_t>& buckets, SpatialHash& h) {
  std::fill(h.count.begin(), h.count.end(), 0u);
  for (uint32_t b : buckets) ++h.count[b];
}

void scan_cells(SpatialHash& h) {
  uint32_t sum = 0;
  for (uint32_t b = 0; b < h.table_size; ++b) {
    h.start[b] = sum;
    sum += h.count[b];
  }
  h.start[h.table_size] = sum;
}

void fill_cells(const std::vector<uint32_t>& buckets, const std::vector<uint32_t>& fill_order, SpatialHash& h) {
  std::vector<uint32_t> cursor(h.start.begin(), h.start.end() - 1);
  for (uint32_t i : fill_order) h.entries[cursor[buckets[i]]++] = i;
  // Ascending ids within a bucket make every later sum independent of the fill order.
  for (uint32_t b = 0; b < h.table_size; ++b)
    std::sort(h.entries.begin() + h.start[b], h.entries.begin() + h.start[b + 1]);
}

}  // namespace clothsim

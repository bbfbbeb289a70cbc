#include "reference/spatial_hash.hpp"

#include <algorithm>

namespace clothsim {

uint32_t hash_table_size(uint32_t particles) {
  // A load factor up to 1: a larger table spends more on clearing, scanning and sorting
  // buckets than it saves on candidates from other cells (measured at 256^2 on llvmpipe).
  uint32_t size = 4;  // three adjacent buckets must be distinct (hash_cell)
  while (size < particles) size <<= 1;
  return size;
}

SpatialHash make_spatial_hash(uint32_t particles) {
  SpatialHash h;
  h.table_size = hash_table_size(particles);
  h.count.assign(h.table_size, 0);
  h.start.assign(h.table_size + 1, 0);
  h.entries.assign(particles, 0);
  return h;
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
  // The counts become the per-bucket cursors, as on the GPU: after the fill they are the counts again.
  std::fill(h.count.begin(), h.count.end(), 0u);
  for (uint32_t i : fill_order) h.entries[h.start[buckets[i]] + h.count[buckets[i]]++] = i;
}

void sort_cells(SpatialHash& h) {
  // Ascending ids within a bucket make every later sum independent of the fill order.
  for (uint32_t b = 0; b < h.table_size; ++b)
    std::sort(h.entries.begin() + h.start[b], h.entries.begin() + h.start[b + 1]);
}

}  // namespace clothsim

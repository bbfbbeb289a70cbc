// Exclusive prefix sum of a uint buffer on the GPU, any length: chunks of SCAN_CHUNK scanned
// serially by one invocation each (scan_cells.comp) per level, the chunk totals scanned
// recursively, then added back
// (add_scan_offsets.comp). Level buffers are sized once for the largest length.
#pragma once

#include <filesystem>
#include <vector>

#include "objects.hpp"
#include "../../compute/layout.glsl"
#include "program.hpp"

namespace clothsim {

// Work issued to the GPU, for the bench's dispatch and barrier counts.
struct GpuCounters {
  long dispatches = 0, barriers = 0;
};

class PrefixScan {
 public:
  static constexpr unsigned kBlock = SCAN_CHUNK;  // elements per invocation of scan_cells

  PrefixScan(const std::filesystem::path& compute_dir, size_t max_count);
  // Scans the first `count` uints of `data` in place (count <= max_count).
  void scan(const gl::Buffer& data, size_t count);
  int dispatches(size_t count) const;  // for the dispatch/barrier count of a frame
  const GpuCounters& counters() const { return counters_; }
  size_t memory_bytes() const;

 private:
  void scan_level(const gl::Buffer& data, size_t count, size_t level);

  gl::Program scan_, add_offsets_;
  std::vector<gl::Buffer> sums_;  // sums_[k]: block totals of level k
  GpuCounters counters_;
};

}  // namespace clothsim

#include "prefix_scan.hpp"

#include <stdexcept>
#include <string>

#include "../../compute/layout.glsl"

namespace clothsim {
namespace {
size_t blocks_for(size_t count) { return (count + PrefixScan::kBlock - 1) / PrefixScan::kBlock; }
}  // namespace

PrefixScan::PrefixScan(const std::filesystem::path& dir, size_t max_count)
    : scan_(gl::Program::compute(dir / "scan_cells.comp", {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}})),
      add_offsets_(gl::Program::compute(dir / "add_scan_offsets.comp",
                                        {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}})) {
  // One sums buffer per level until a level fits in one block.
  for (size_t n = std::max<size_t>(max_count, 1);; n = blocks_for(n)) {
    gl::Buffer b("scan sums");
    b.allocate(blocks_for(n) * sizeof(uint32_t));
    sums_.push_back(std::move(b));
    if (n <= kBlock) break;
  }
}

void PrefixScan::scan(const gl::Buffer& data, size_t count) {
  if (count == 0) return;
  if (count * sizeof(uint32_t) > data.size()) throw std::out_of_range("PrefixScan::scan: count exceeds the buffer");
  scan_level(data, count, 0);
}

void PrefixScan::scan_level(const gl::Buffer& data, size_t count, size_t level) {
  if (level >= sums_.size()) throw std::out_of_range("PrefixScan::scan: count exceeds max_count");
  const size_t blocks = blocks_for(count);
  data.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SCAN_DATA);
  sums_[level].bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SCAN_SUMS);
  scan_.set("u_count", unsigned(count));
  scan_.dispatch(gl::workgroups_for(blocks, WORKGROUP_SIZE));
  counters_.dispatches += 1;
  counters_.barriers += 1;
  // The next level scans the block sums (or add_scan_offsets reads them).
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  if (blocks == 1) return;
  scan_level(sums_[level], blocks, level + 1);
  data.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SCAN_DATA);
  sums_[level].bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SCAN_SUMS);
  add_offsets_.set("u_count", unsigned(count));
  add_offsets_.dispatch(gl::workgroups_for(count, WORKGROUP_SIZE));
  counters_.dispatches += 1;
  counters_.barriers += 1;
  // fill_cells (or the level above) reads the finished prefix sums next.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

size_t PrefixScan::memory_bytes() const {
  size_t total = 0;
  for (const auto& b : sums_) total += b.size();
  return total;
}

int PrefixScan::dispatches(size_t count) const {
  int d = 1;
  for (size_t n = count; blocks_for(n) > 1; n = blocks_for(n)) d += 2;
  return d;
}

}  // namespace clothsim

#include "gpu_divergence.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "debug_output.hpp"
#include "../../compute/layout.glsl"
#include "../../compute/shared/divergence.glsl"

namespace clothsim {
namespace {

using shared::from_ordered_bits;
using shared::ordered_bits;

static_assert(sizeof(layout::LastGoodHeader) == sizeof(glm::vec4), "the kept positions start one vec4 in");

ClothBounds decode(const layout::FrameBounds& b) {
  ClothBounds out;
  out.finite = b.lo.w == 0;
  for (int k = 0; k < 3; ++k) {
    out.lo[k] = from_ordered_bits(b.lo[k]);
    out.hi[k] = from_ordered_bits(b.hi[k]);
  }
  return out;
}

gl::Program load(const std::filesystem::path& dir, const char* name) {
  return gl::Program::compute(dir / fmt::format("{}.comp", name),
                              {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}});
}

}  // namespace

GpuDivergenceGuard::GpuDivergenceGuard(const Scene& scene, const ClothModel& model, const std::filesystem::path& dir)
    : count_(size_t(model.count())),
      limits_(divergence_limits(scene, model)),
      check_divergence_(load(dir, "check_divergence")),
      keep_last_good_(load(dir, "keep_last_good")) {
  // The empty box, +Inf to -Inf, that every frame's reduction starts from.
  const float inf = std::numeric_limits<float>::infinity();
  layout::FrameBounds empty{};
  empty.lo = glm::uvec4(ordered_bits(inf), ordered_bits(inf), ordered_bits(inf), 0u);
  empty.hi = glm::uvec4(ordered_bits(-inf), ordered_bits(-inf), ordered_bits(-inf), 0u);
  empty_bounds_.allocate(sizeof(empty), &empty, GL_STATIC_DRAW);
  for (Slot& s : slots_) s.bounds.allocate(sizeof(empty), &empty);
  last_good_.allocate(sizeof(layout::LastGoodHeader) + count_ * sizeof(glm::vec4));
  check_divergence_.set("u_count", unsigned(count_));
  keep_last_good_.set("u_count", unsigned(count_));
  keep_last_good_.set("u_centre", limits_.centre);
  keep_last_good_.set("u_limit", limits_.limit);
  std::vector<glm::vec4> initial(count_);
  for (size_t i = 0; i < count_; ++i)
    initial[i] = glm::vec4(glm::vec3(model.initial[i]), model.pinned[i] ? 0.f : float(1.0 / model.mass[i]));
  restart(initial, 0);
}

void GpuDivergenceGuard::check(const gl::Buffer& positions) {
  Slot& slot = slots_[size_t(++frame_ % 2)];
  slot.fence = {};  // a result nobody took is dropped
  slot.frame = frame_;
  // A buffer copy, ordered before the dispatch below without a barrier.
  slot.bounds.copy_from(empty_bounds_, 0, 0, sizeof(layout::FrameBounds));
  positions.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CHECKED_POSITIONS);
  slot.bounds.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_FRAME_BOUNDS);
  last_good_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_LAST_GOOD);
  check_divergence_.dispatch(gl::workgroups_for(count_, WORKGROUP_SIZE));
  // keep_last_good reads the finished bounds next, and take() reads them back later.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  keep_last_good_.set("u_frame", unsigned(frame_));
  keep_last_good_.dispatch(gl::workgroups_for(count_, WORKGROUP_SIZE));
  // The next frame's passes overwrite the positions just copied, and last_good() reads the copy back.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  slot.fence = gl::Fence::insert();
  counters_.dispatches += kDispatchesPerFrame;
  counters_.barriers += 2;
}

std::vector<FrameCheck> GpuDivergenceGuard::take(bool all) {
  std::vector<Slot*> pending;
  for (Slot& s : slots_)
    if (s.fence) pending.push_back(&s);
  std::sort(pending.begin(), pending.end(), [](const Slot* a, const Slot* b) { return a->frame < b->frame; });
  std::vector<FrameCheck> out;
  for (Slot* s : pending) {
    // The newest frame may still be running: take it only if done, so the GPU keeps a frame
    // queued while the host waits for the one before.
    if (all || s->frame < frame_) s->fence.wait();
    else if (!s->fence.signalled()) break;
    layout::FrameBounds b;
    s->bounds.download(0, sizeof(b), &b);
    s->fence = {};
    out.push_back({s->frame, decode(b)});
  }
  if (gl::poll_out_of_memory())
    throw gl::OutOfMemoryError(fmt::format("GL_OUT_OF_MEMORY: the GPU driver ran out of memory during frame {}",
                                           frame_));
  return out;
}

std::vector<glm::vec4> GpuDivergenceGuard::last_good(int* frame) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // a read-back of keep_last_good's writes
  layout::LastGoodHeader header;
  last_good_.download(0, sizeof(header), &header);
  if (frame) *frame = int(header.state.y);
  return gl::download_vector<glm::vec4>(last_good_, 1, count_);
}

void GpuDivergenceGuard::restart(const std::vector<glm::vec4>& positions, int frame) {
  for (Slot& s : slots_) s.fence = {};
  frame_ = frame;
  const layout::LastGoodHeader header{glm::uvec4(0u, unsigned(frame), 0u, 0u)};
  last_good_.upload(0, sizeof(header), &header);
  last_good_.upload(sizeof(header), std::min(positions.size(), count_) * sizeof(glm::vec4), positions.data());
}

size_t GpuDivergenceGuard::memory_bytes() const {
  return empty_bounds_.size() + last_good_.size() + slots_.size() * slots_[0].bounds.size();
}

}  // namespace clothsim

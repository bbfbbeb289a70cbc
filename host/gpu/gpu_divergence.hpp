// The divergence guard on the GPU (divergence.hpp has the model). After every frame,
// check_divergence reduces the positions into a small FrameBounds buffer and keep_last_good
// copies them aside while every frame so far has passed; a fence marks the frame. The host
// reads a frame's 32 bytes only once its fence has signalled, so the GPU never waits for the
// host and nothing is read back per frame but those bytes.
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include <glm/vec4.hpp>

#include "analysis/divergence.hpp"
#include "objects.hpp"
#include "prefix_scan.hpp"
#include "program.hpp"

namespace clothsim {

class GpuDivergenceGuard {
 public:
  static constexpr int kDispatchesPerFrame = 2;  // check_divergence, keep_last_good

  GpuDivergenceGuard(const Scene& scene, const ClothModel& model, const std::filesystem::path& compute_dir);

  // Queues the checks of the frame just simulated (`positions`: the simulator's current
  // buffer, after the frame's last barrier). Two dispatches, no waiting.
  void check(const gl::Buffer& positions);
  // The results not yet taken, oldest first (see Backend::take_checks): every frame but the
  // newest is waited for, the newest taken only if already done, unless `all`. Results not
  // taken within two frames are dropped. Also drains glGetError once, so a GL_OUT_OF_MEMORY
  // of the read-back throws gl::OutOfMemoryError here (any other code is thrown by the next
  // GpuSimulator::step_frame, which checks every frame's passes itself).
  std::vector<FrameCheck> take(bool all);
  // The kept copy (a read-back, not for every frame): the newest frame that passed before
  // any failed; 0 is the initial state.
  std::vector<glm::vec4> last_good(int* frame);
  // Starts over from `positions` as frame `frame`: the initial state as frame 0 after a reset,
  // or a kept frame the viewer has restored. Forgets pending results and any failure.
  void restart(const std::vector<glm::vec4>& positions, int frame);

  int frame() const { return frame_; }  // the frame checked last
  const GpuCounters& counters() const { return counters_; }
  size_t memory_bytes() const;

 private:
  struct Slot {
    gl::Buffer bounds{"frame bounds"};
    gl::Fence fence;  // empty: no result waiting
    int frame = 0;
  };

  const size_t count_;
  const DivergenceLimits limits_;
  gl::Program check_divergence_, keep_last_good_;
  gl::Buffer empty_bounds_{"empty frame bounds"}, last_good_{"last good positions"};
  std::array<Slot, 2> slots_;  // frame f uses slots_[f % 2]
  int frame_ = 0;
  GpuCounters counters_;
};

}  // namespace clothsim

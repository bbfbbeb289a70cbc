// Milliseconds per pass of one drawn frame: GL timestamp queries at the passes' boundaries
// where the driver has a GPU timer (read a frame late, so nothing waits), else (llvmpipe,
// whose timestamps are not the rasterizer's) glFinish and a steady clock at each boundary.
// Timestamps, not GL_TIME_ELAPSED, because spans nest (the viewer times the simulation and the
// whole draw, the renderer each of its passes inside it) and elapsed-time queries do not.
#pragma once

#include <glad/gl.h>

#include <array>
#include <chrono>

namespace clothsim {

template <int Passes> class PassClock {
 public:
  // software: a rasterizer on the CPU (llvmpipe), whose timestamps are taken when commands
  // are queued, not run; it gets the clock from the start. Callers pass
  // gl::gl_renderer_is_llvmpipe(), plain llvmpipe only: zink on lavapipe stamps each command
  // as lavapipe runs it (pinned2 at 640x480: 388 ms a frame by its queries, 425 by the clock),
  // so there the queries a GPU takes run (scripts/test-zink checks that they did).
  explicit PassClock(bool software) : use_queries_(!software) { glGenQueries(GLsizei(queries_.size()), queries_.data()); }
  ~PassClock() { glDeleteQueries(GLsizei(queries_.size()), queries_.data()); }
  PassClock(const PassClock&) = delete;
  PassClock& operator=(const PassClock&) = delete;

  // Boundary b (0 before the first pass, Passes after the last).
  void mark(int b) {
    if (use_queries_) {
      glQueryCounter(queries_[size_t(current_ * (Passes + 1) + b)], GL_TIMESTAMP);
      return;
    }
    glFinish();
    clock_[size_t(b)] = std::chrono::steady_clock::now();
  }
  // After the last mark: the newest finished milliseconds of each pass (a frame late with queries).
  const std::array<double, Passes>& finish() {
    if (!use_queries_) {
      for (int p = 0; p < Passes; ++p)
        ms_[size_t(p)] = std::chrono::duration<double, std::milli>(clock_[size_t(p + 1)] - clock_[size_t(p)]).count();
      return ms_;
    }
    const int previous = 1 - current_;
    if (frames_++ > 0) {
      std::array<GLuint64, Passes + 1> t{};
      for (int b = 0; b <= Passes; ++b)
        glGetQueryObjectui64v(queries_[size_t(previous * (Passes + 1) + b)], GL_QUERY_RESULT, &t[size_t(b)]);
      // A driver without a GPU timer reads the same (0) at every boundary: switch to the clock.
      if (t[Passes] == t[0] && ++zero_reads_ > 3) use_queries_ = false;
      for (int p = 0; p < Passes; ++p) ms_[size_t(p)] = double(t[size_t(p + 1)] - t[size_t(p)]) * 1e-6;
    }
    current_ = previous;
    return ms_;
  }
  bool uses_queries() const { return use_queries_; }

 private:
  std::array<GLuint, 2 * (Passes + 1)> queries_{};
  std::array<std::chrono::steady_clock::time_point, Passes + 1> clock_{};
  std::array<double, Passes> ms_{};
  int current_ = 0, frames_ = 0, zero_reads_ = 0;
  bool use_queries_ = true;
};

}  // namespace clothsim

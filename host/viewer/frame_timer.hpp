// Milliseconds spent on a span of GL work: GL_TIME_ELAPSED queries where the driver has a
// GPU timer, else (llvmpipe reports 0) glFinish around a steady clock.
#pragma once

#include <glad/gl.h>

#include <chrono>

namespace clothsim {

class FrameTimer {
 public:
  FrameTimer() { glGenQueries(2, queries_); }
  ~FrameTimer() { glDeleteQueries(2, queries_); }
  FrameTimer(const FrameTimer&) = delete;
  FrameTimer& operator=(const FrameTimer&) = delete;

  void begin() {
    if (use_queries_) glBeginQuery(GL_TIME_ELAPSED, queries_[current_]);
    else { glFinish(); start_ = std::chrono::steady_clock::now(); }
  }
  // Ends the span; returns the latest finished measurement in ms (a frame late with queries).
  double end() {
    if (!use_queries_) {
      glFinish();
      last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
      return last_ms_;
    }
    glEndQuery(GL_TIME_ELAPSED);
    const GLuint previous = queries_[1 - current_];
    if (frames_++ > 0) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(previous, GL_QUERY_RESULT, &ns);
      // A driver without a GPU timer reads 0 every time: switch to the CPU clock.
      if (ns == 0 && ++zero_reads_ > 3) use_queries_ = false;
      last_ms_ = double(ns) * 1e-6;
    }
    current_ = 1 - current_;
    return last_ms_;
  }
  bool uses_queries() const { return use_queries_; }

 private:
  GLuint queries_[2] = {0, 0};
  int current_ = 0, frames_ = 0, zero_reads_ = 0;
  bool use_queries_ = true;
  double last_ms_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace clothsim

// Where a run's time goes, pass by pass (simulate --profile): each pass's wall time summed over
// the run and how often it ran, in the order the passes first ran. The backends time their own
// passes into it (CpuBackend around the reference's functions, GpuSimulator around the pass
// table's stage rows with a glFinish before and after each, so a pass's time is its own and not
// the queue's); timing never changes what a pass computes. A pass timed inside another (the
// contact list's collide_objects inside predict's stage) is its own row, and the outer row keeps
// only the rest: every row is exclusive, so the rows add up to the time measured.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace clothsim {

class PassProfile {
 public:
  struct Row {
    std::string name;
    double seconds = 0;
    int64_t runs = 0;
  };
  void add(std::string_view name, double seconds) {
    Row* row = nullptr;
    for (Row& r : rows_)
      if (r.name == name) row = &r;
    if (!row) row = &rows_.emplace_back(Row{std::string(name)});
    row->seconds += seconds;
    ++row->runs;
  }
  const std::vector<Row>& rows() const { return rows_; }
  // Brackets a timed pass: what passes timed inside it took is taken off its own row (add).
  double enter() { return std::exchange(inner_, 0.0); }
  void leave(std::string_view name, double seconds, double outer_inner) {
    add(name, seconds - inner_);
    inner_ = outer_inner + seconds;
  }
  double total_seconds() const {
    double sum = 0;
    for (const Row& r : rows_) sum += r.seconds;
    return sum;
  }

 private:
  std::vector<Row> rows_;
  double inner_ = 0;  // seconds of the passes timed inside the one being timed
};

// Runs f; with a profile, timed as `name` between two calls of `finish` (what waits for the work
// queued so far: glFinish on the GPU, nothing on the CPU).
template <class F, class Finish> void profiled(PassProfile* profile, std::string_view name, F&& f, Finish&& finish) {
  if (!profile) return void(f());
  finish();
  const double outer_inner = profile->enter();
  const auto t0 = std::chrono::steady_clock::now();
  f();
  finish();
  profile->leave(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), outer_inner);
}
template <class F> void profiled(PassProfile* profile, std::string_view name, F&& f) {
  profiled(profile, name, std::forward<F>(f), [] {});
}

}  // namespace clothsim

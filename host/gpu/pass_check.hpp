// Per-pass comparison of the GPU simulator with the CPU reference from identical states.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gpu_simulator.hpp"

namespace clothsim {

struct Deviation {
  double max = 0, rms = 0;
  bool bitwise = true;
};
// Distance between matching particles (xyz only), max and RMS; a NaN counts as infinite.
template <class A, class B> Deviation deviation(const std::vector<A>& a, const std::vector<B>& b) {
  Deviation d;
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const glm::dvec3 e = glm::dvec3(a[i]) - glm::dvec3(b[i]);
    const double len = std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
    d.max = std::isnan(len) ? INFINITY : std::max(d.max, len);
    sum += len * len;
    d.bitwise = d.bitwise && glm::dvec4(a[i]) == glm::dvec4(b[i]);
  }
  d.rms = a.empty() ? 0 : std::sqrt(sum / double(a.size()));
  return d;
}

struct PassError {
  std::string pass;
  double max_error = 0;  // metres; forces are converted to the displacement they cause in one substep
  bool bitwise = true;
  // The hash stages produce integers, which must agree exactly on any GPU: then max_error is
  // 0 when they do and infinite when they do not, and `differing` counts the elements.
  bool integers = false;
  size_t differing = 0;
};

// Runs the CPU (float) for `warmup_frames`, then checks each pass of one substep (and the
// normals) on the GPU against the CPU, each from the CPU's state before that pass: the
// unfused passes, the fused ones the step runs, and with self-collision each stage of the
// hash (count_cells, scan_cells, fill_cells, sort_cells) and resolve_self_contacts.
std::vector<PassError> check_passes(const Scene& scene, const ClothModel& model, GpuSimulator& gpu,
                                    int warmup_frames);

}  // namespace clothsim

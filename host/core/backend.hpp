// A simulation backend: something that advances the cloth one rendered frame at a time
// and can hand back a copy of its state on request (export, stats, validation).
#pragma once

#include <memory>
#include <string>

#include "diagnostics.hpp"
#include "reference.hpp"

namespace clothsim {

class Backend {
 public:
  virtual ~Backend() = default;
  // simulation_steps substeps, then the normals (once per rendered frame).
  virtual void step_frame() = 0;
  // A copy of the state. On the GPU this is the only read-back, so call it only when needed.
  virtual ClothSnapshot snapshot() = 0;
  virtual std::string name() const = 0;
};

// The CPU reference as a backend, in float (what the GPU computes) or double.
template <class R> class CpuBackend final : public Backend {
 public:
  CpuBackend(const Scene& scene, const ClothModel& model)
      : model_(model), constants_(make_constants<R>(scene, model)), state_(initial_state<R>(model)) {}

  void step_frame() override {
    for (int k = 0; k < int(constants_.steps); ++k) step(model_, constants_, state_);
    compute_normals(model_, state_);
  }
  ClothSnapshot snapshot() override {
    ClothSnapshot s;
    for (auto& p : state_.pos) s.pos.emplace_back(p);
    for (auto& p : state_.prev) s.prev.emplace_back(p);
    for (auto& p : state_.normal) s.normal.emplace_back(p);
    return s;
  }
  std::string name() const override { return sizeof(R) == 4 ? "cpu (float)" : "cpu (double)"; }

  State<R>& state() { return state_; }
  const Constants<R>& constants() const { return constants_; }

 private:
  const ClothModel& model_;
  Constants<R> constants_;
  State<R> state_;
};

}  // namespace clothsim

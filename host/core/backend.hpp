// A simulation backend: something that advances the cloth one rendered frame at a time,
// checks every frame for divergence (divergence.hpp), and can hand back a copy of its state
// on request (export, stats, validation), or its raw state for a checkpoint (checkpoint.hpp).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "export/checkpoint.hpp"
#include "analysis/diagnostics.hpp"
#include "analysis/divergence.hpp"
#include "reference/reference.hpp"
#include "reference/reference_skinning.hpp"

namespace clothsim {

class Backend {
 public:
  virtual ~Backend() = default;
  // simulation_steps substeps, then the normals (once per rendered frame).
  virtual void step_frame() = 0;
  // A copy of the state. On the GPU this is the only read-back, so call it only when needed.
  virtual ClothSnapshot snapshot() = 0;
  virtual std::string name() const = 0;
  // The divergence checks not yet taken, oldest first, each frame once. The CPU has checked
  // the frame just stepped; the GPU hands over each result when it is ready, at most one frame
  // late (it waits for the previous frame if needed, never for the newest), or with `all`
  // every frame stepped so far. Results not taken within two frames are dropped, so a caller
  // that never looks (bench, validate) keeps nothing.
  virtual std::vector<FrameCheck> take_checks(bool all) = 0;
  // The newest frame that passed its check before any failed (0 = the initial state), with
  // CPU-computed normals: what a diverged run exports instead of NaNs.
  virtual ClothSnapshot last_good(int* frame) = 0;
  // The raw state streams in the backend's own scalar, with the frames and seconds simulated:
  // loading them into a fresh backend of the same cloth continues the run bit for bit.
  virtual SavedState save_state() = 0;
  // Continues from `saved` (check_fits it first): the next step_frame is frame saved.frame + 1,
  // and the divergence guard starts over with the loaded positions as its last good frame.
  virtual void load_state(const SavedState& saved) = 0;
  virtual int scalar_bytes() const = 0;  // 4 (float) or 8 (double)
  // Simulated seconds so far: the time of the state snapshot() returns (the end of the last
  // substep), where the keyframed colliders were for its collision passes.
  virtual double time() const = 0;
  // enforce_stretch_limit's settling passes run so far (0 without them; the GPU reads it back).
  virtual uint64_t stretch_settling_passes() const { return 0; }
  // Times every pass of the frames that follow into `profile` (null: no longer), each pass on its
  // own (simulate --profile); the state evolves bit for bit as without.
  virtual void set_profile(PassProfile* profile) = 0;
};

// The CPU reference as a backend, in float (what the GPU computes) or double.
template <class R> class CpuBackend final : public Backend {
 public:
  CpuBackend(const Scene& scene, const ClothModel& model)
      : model_(model), constants_(make_constants<R>(scene, model)), state_(initial_state<R>(model)),
        limits_(divergence_limits(scene, model)), dt_(scene.dt()) {
    kept_.pos = state_.pos;
    state_.nearest.assign(size_t(model.count()) * constants_.skin_meshes, kNoParticle);  // (skinned colliders)
  }

  void step_frame() override {
    for (int k = 0; k < int(constants_.steps); ++k) {
      prepare_substep();
      step(model_, constants_, state_, profile_);
      time_ += dt_;  // per substep, exactly as GpuSimulator::step counts it
    }
    profiled(profile_, "compute_normals", [&] { compute_normals(model_, state_); });
    FrameCheck check{++frame_, {}};
    profiled(profile_, "check_divergence", [&] {
      check.bounds = check_divergence(state_.pos);
      keep_last_good(check.bounds, limits_, check.frame, state_.pos, kept_);
    });
    if (checks_.size() >= 2) checks_.erase(checks_.begin());
    checks_.push_back(check);
  }
  std::vector<FrameCheck> take_checks(bool) override { return std::exchange(checks_, {}); }
  uint64_t stretch_settling_passes() const override { return state_.stretch_settling_passes; }
  void set_profile(PassProfile* profile) override { profile_ = profile; }
  ClothSnapshot last_good(int* frame) override {
    if (frame) *frame = kept_.frame;
    return snapshot_of_positions(model_, kept_.pos);
  }
  ClothSnapshot snapshot() override {
    ClothSnapshot s;
    for (auto& p : state_.pos) s.pos.emplace_back(p);
    for (auto& d : state_.disp) s.disp.emplace_back(d);
    for (auto& p : state_.normal) s.normal.emplace_back(p);
    return s;
  }
  std::string name() const override { return sizeof(R) == 4 ? "cpu (float)" : "cpu (double)"; }
  SavedState save_state() override { return save_streams(state_, frame_, time_, dt_); }
  // A state saved with another substep length has its displacements rescaled to this one's.
  void load_state(const SavedState& saved) override {
    load_streams(saved, state_, dt_);
    compute_normals(model_, state_);
    frame_ = int(saved.frame);
    time_ = saved.time;
    kept_ = {state_.pos, frame_, false};
    checks_.clear();
  }
  int scalar_bytes() const override { return int(sizeof(R)); }

  State<R>& state() { return state_; }
  const Constants<R>& constants() const { return constants_; }
  // The moving parts (colliders, pins, gusts) set for the substep that starts now.
  void prepare_substep() {
    if (constants_.timeline.moves()) profiled(profile_, "substep control", [&] { set_substep_time(constants_, time_); });
    if (!constants_.timeline.skins.empty())  // the twins of skin_colliders.comp and fit_collider_boxes.comp
      profiled(profile_, "skin_colliders", [&] {
        skin_colliders(constants_.control, constants_);
        fit_collider_boxes(constants_.control, constants_);
      });
  }
  double time() const override { return time_; }

 private:
  const ClothModel& model_;
  Constants<R> constants_;
  State<R> state_;
  DivergenceLimits limits_;
  KeptFrame<R> kept_;
  double dt_;
  int frame_ = 0;
  double time_ = 0;  // simulated seconds
  std::vector<FrameCheck> checks_;  // not yet taken
  PassProfile* profile_ = nullptr;  // simulate --profile's, while it times
};

}  // namespace clothsim

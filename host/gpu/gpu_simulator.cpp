// The simulator: construction, the step (its entries are the pass table's stage rows), memory.
#include "gpu_simulator.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>

#include <fmt/format.h>

#include "debug_output.hpp"


namespace clothsim {
GpuSimulator::GpuSimulator(const Scene& scene, const ClothModel& model, const std::filesystem::path& dir)
    : state_(scene, model),  // checks the GPU's limits first
      constants_(make_constants<float>(scene, model)),
      passes_(state_, constants_, scene, model, dir),
      masses_(particle_masses(scene, model)),
      dt_(scene.dt()) {
  state_.upload_model();
  state_.upload_rest_positions(constants_);
  state_.upload_control(constants_);  // the block and the colliders
  state_.upload_anchors(constants_);
  state_.upload_materials(constants_);
  state_.step_params_.allocate(sizeof(layout::StepParams), &constants_.params(), GL_DYNAMIC_DRAW);  // as it is
  state_.allocate_scratch(constants_);
  upload(initial_state<float>(model));  // attaches the views
  passes_.ensure_multigrid();
  run(PassId::compute_normals);
}

GpuSimulator::~GpuSimulator() = default;

size_t GpuSimulator::memory_bytes() const {
  return state_.buffer_bytes() + passes_.scan_.memory_bytes() + passes_.guard_.memory_bytes();
}

namespace {

// Sets a flag for a scope, cleared however the scope ends (a GL error throws out of a frame).
struct ScopedFlag {
  explicit ScopedFlag(bool& flag) : flag_(flag) { flag_ = true; }
  ~ScopedFlag() { flag_ = false; }
  ScopedFlag(const ScopedFlag&) = delete;
  ScopedFlag& operator=(const ScopedFlag&) = delete;
  bool& flag_;
};

}  // namespace

void GpuSimulator::step() {
  // Moving colliders, pins and gusts: the substep's control for its time (not the parameter block).
  if (constants_.timeline.moves()) passes_.timed("substep control", [&] { apply_substep_time(); });
  passes_.ensure_multigrid();  // (after a live edit rebuilt the hierarchy) before the bindings
  state_.bind_all();  // once: nothing in the step binds over these (swap_positions rebinds its two)
  {
    const ScopedFlag in_step(passes_.in_step_);
    const uint16_t features = passes_.features();
    for (const PassRow& r : kPasses)
      if (r.stage && runs(r, features)) passes_.timed(stage_name(r), [&] { run_stage(r.id); });
  }
  time_ += dt_;  // per substep, exactly as CpuBackend counts it
}

void GpuSimulator::run_stage(PassId stage) {
  if (!runs(row(stage), passes_.features())) return;
  // collide_objects reads only a particle's own position and displacement, so it rides along
  // with the last per-particle pass before the constraints: the first pass without
  // self-collision, the response with it.
  const bool colliders = constants_.has_colliders(), self = constants_.self_collision;
  switch (stage) {
    case PassId::advance:
    case PassId::predict: return passes_.run(stage, {.collide_objects = colliders && !self});
    case PassId::resolve_self_contacts: return passes_.run(stage, {.collide_objects = colliders});
    case PassId::restrict_residuals: return passes_.cycle_levels();  // the V-cycle down and up
    default: return passes_.run(stage);  // stretch_fixed_passes: the whole enforce_stretch_limit
  }
}

void GpuSimulator::step_frame() {
  const int frame = passes_.guard_.frame() + 1;
  // GL errors, in release builds too: glGetError reads the context's error flags, with no wait
  // for the GPU (unlike glFinish) and no read-back. First what was raised since the previous
  // frame's check by someone else (the renderer, a read-back, an edit), so it is not blamed on
  // the passes; then, after the passes, theirs.
  gl::check_gl_errors_lazily([&] {
    return fmt::format("before frame {} on the GPU: raised by a GL call outside the simulation since the previous "
                       "frame's check (rendering, a read-back or an edit), not by its passes",
                       frame);
  });
  {
    const ScopedFlag in_frame(passes_.in_frame_);
    for (passes_.substep_ = 0; passes_.substep_ < int(constants_.steps); ++passes_.substep_) step();
    passes_.timed("compute_normals", [&] { run(PassId::compute_normals); });
  }
  passes_.timed("check_divergence", [&] { passes_.guard_.check(state_.positions_); });
  gl::check_gl_errors_lazily([&] {
    return fmt::format("in frame {} on the GPU: raised by one of the frame's passes ({} substeps of {}; then "
                       "compute_normals, check_divergence, keep_last_good). A debug build (-DCMAKE_BUILD_TYPE=Debug) "
                       "names the pass and the GL call",
                       frame, int(constants_.steps), passes_.pass_list());
  });
}

GpuBackend::GpuBackend(std::unique_ptr<gl::GlContext> context, const Scene& scene, const ClothModel& model,
                       const std::filesystem::path& compute_dir)
    : context_(std::move(context)), model_(model),
      sim_(std::make_unique<GpuSimulator>(scene, model, compute_dir)) {}

ClothSnapshot GpuBackend::snapshot() {
  State<float> s;
  sim_->download(s);
  ClothSnapshot out;
  for (auto& p : s.pos) out.pos.emplace_back(p);
  for (auto& d : s.disp) out.disp.emplace_back(d);
  for (auto& p : s.normal) out.normal.emplace_back(p);
  return out;
}

std::string GpuBackend::name() const { return fmt::format("gpu ({})", gl::gl_renderer_string()); }

std::filesystem::path find_project_root(const std::filesystem::path& hint) {
  namespace fs = std::filesystem;
  auto has_compute = [](const fs::path& p) { return !p.empty() && fs::exists(p / "compute" / "layout.glsl"); };
  if (!hint.empty()) return hint;
  if (const char* env = std::getenv("CLOTHSIM_ROOT"); env && has_compute(env)) return env;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (fs::path p = exe.parent_path(); !p.empty() && p != p.root_path(); p = p.parent_path())
      if (has_compute(p)) return p;
  }
  if (has_compute(CLOTHSIM_SOURCE_DIR)) return CLOTHSIM_SOURCE_DIR;
  throw std::runtime_error(
      "cannot find the project's shader files (compute/layout.glsl): run from the source tree, "
      "pass -r ROOT, or set CLOTHSIM_ROOT");
}

}  // namespace clothsim

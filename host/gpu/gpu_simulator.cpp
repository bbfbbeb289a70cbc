// The simulator: construction, the step (its entries are the pass table's stage rows), memory.
#include "gpu_simulator.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>

#include <fmt/format.h>

#include "debug_output.hpp"


namespace clothsim {
GpuSimulator::GpuSimulator(const Scene& scene, const ClothModel& model, const std::filesystem::path& dir)
    : GpuPasses(scene, model, dir),
      masses_(particle_masses(scene, model)),
      dt_(scene.dt()) {
  const size_t n = model.count();
  upload_model();
  upload_rest_positions();

  upload_colliders();
  upload_anchors();
  upload_materials();
  step_params_.allocate(sizeof(layout::StepParams), &constants_.params(), GL_DYNAMIC_DRAW);  // as it is
  forces_.allocate(n * sizeof(glm::vec4));
  // A storage buffer may not be empty when bound: one dummy element without wind.
  wind_forces_.allocate((constants_.wind_enabled ? n : 1) * sizeof(glm::vec4));
  // The hash table is sized once; start[table_size] is the total, always n.
  table_size_ = constants_.table_size;
  cell_count_.allocate(table_size_ * sizeof(uint32_t));
  std::vector<uint32_t> start(table_size_ + 1, 0);
  start.back() = uint32_t(n);
  gl::upload_vector(cell_start_, start);
  cell_entries_.allocate(n * sizeof(uint32_t));
  sorted_positions_.allocate(n * sizeof(glm::vec4));
  normals_.allocate(n * sizeof(glm::vec4));
  no_offsets_.allocate(sizeof(glm::vec4));
  upload(initial_state<float>(model));  // attaches the views
  ensure_multigrid();
  run(PassId::compute_normals);
}

GpuSimulator::~GpuSimulator() = default;

void GpuSimulator::upload_rest_positions() {
  // Only the bounded contact reads them (one dummy texel otherwise: a view may not be empty).
  std::vector<glm::vec4> rest;
  for (const Vec3<float>& r : constants_.rest) rest.push_back({r.x, r.y, r.z, 0.f});
  if (rest.empty()) rest.resize(1);
  gl::upload_vector(rest_positions_, rest, GL_STATIC_DRAW);
  rest_positions_view_.attach(rest_positions_, GL_RGBA32F);
}

void GpuSimulator::upload_materials() {
  std::vector<layout::MaterialTexels> materials;
  for (const MaterialC<float>& mat : constants_.materials)
    materials.push_back({glm::vec4(mat.ks, mat.ks_bending, mat.alpha, mat.alpha_bending),
                         glm::vec4(mat.keep_velocity, float(mat.enabled[0]), float(mat.enabled[1]), float(mat.enabled[2]))});
  std::vector<glm::vec4> particles;
  for (size_t i = 0; i < constants_.mass.size(); ++i) particles.push_back({constants_.mass[i], float(model_.material[i]), 0.f, 0.f});
  gl::upload_vector(materials_, materials, GL_DYNAMIC_DRAW);
  gl::upload_vector(particles_, particles, GL_DYNAMIC_DRAW);
  materials_view_.attach(materials_, GL_RGBA32F);
  particles_view_.attach(particles_, GL_RGBA32F);
}

size_t GpuSimulator::memory_bytes() const {
  return buffer_bytes() + scan_.memory_bytes() + guard_.memory_bytes();
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
  // Moving colliders, pins and gusts: the small parameter upload of this substep's time.
  if (constants_.timeline.moves()) apply_substep_time();
  ensure_multigrid();  // (after a live edit rebuilt the hierarchy) before the bindings
  bind_all();  // once: nothing in the step binds over these (swap_positions rebinds its two)
  {
    const ScopedFlag in_step(in_step_);
    const uint16_t features = shape().features;
    for (const PassRow& r : kPasses)
      if (r.stage && runs(r, features)) run_stage(r.id);
  }
  time_ += dt_;  // per substep, exactly as CpuBackend counts it
}

void GpuSimulator::run_stage(PassId stage) {
  if (!runs(row(stage), shape().features)) return;
  // collide_objects reads only a particle's own position and displacement, so it rides along
  // with the last per-particle pass before the constraints: the first pass without
  // self-collision, the response with it.
  const bool colliders = constants_.has_colliders(), self = constants_.self_collision;
  switch (stage) {
    case PassId::advance:
    case PassId::predict: return run(stage, {.collide_objects = colliders && !self});
    case PassId::resolve_self_contacts: return run(stage, {.collide_objects = colliders});
    case PassId::restrict_residuals: return cycle_levels();  // the V-cycle down and up
    default: return run(stage);  // stretch_fixed_passes: the whole enforce_stretch_limit
  }
}

void GpuSimulator::step_frame() {
  const int frame = guard_.frame() + 1;
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
    const ScopedFlag in_frame(in_frame_);
    for (substep_ = 0; substep_ < int(constants_.steps); ++substep_) step();
    run(PassId::compute_normals);
  }
  guard_.check(positions_);
  gl::check_gl_errors_lazily([&] {
    return fmt::format("in frame {} on the GPU: raised by one of the frame's passes ({} substeps of {}; then "
                       "compute_normals, check_divergence, keep_last_good). A debug build (-DCMAKE_BUILD_TYPE=Debug) "
                       "names the pass and the GL call",
                       frame, int(constants_.steps), pass_list());
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

#include "session.hpp"

#include <chrono>
#include <cstring>

#include <fmt/format.h>

#include "camera.hpp"
#include "export/frame_export.hpp"
#include "export/output_plan.hpp"
#include "gpu_simulator.hpp"
#include "image_output.hpp"
#include "renderer.hpp"
#include "run_stats.hpp"
#include "texture.hpp"

namespace clothsim {

struct Session::Current {
  explicit Current(gl::GlContext* c) : context(c) {
    if (context) context->make_current();
  }
  ~Current() {
    if (context) context->release();
  }
  gl::GlContext* context;
};

Session::Session(Scene scene, BackendKind kind)
    : scene_(std::move(scene)), model_(std::make_unique<ClothModel>(build_cloth(scene_))) {
  if (kind == BackendKind::Cpu) {
    backend_ = make_backend(kind, scene_, *model_);
    backend_name_ = backend_->name();
    return;
  }
  context_ = require_headless_context();  // ExitError 3 when there is none
  Current current(context_.get());
  backend_ = std::make_unique<GpuBackend>(nullptr, scene_, *model_, find_project_root() / "compute");
  backend_name_ = backend_->name();
}

Session::~Session() {
  // The GL objects are deleted with their context current.
  Current current(context_.get());
  renderer_.reset();
  backend_.reset();
}

void Session::step(int frames) {
  Current current(context_.get());
  auto stop_if_diverged = [&](const std::vector<FrameCheck>& checks) {
    for (const FrameCheck& check : checks)
      if (const auto message = divergence_message(scene_, *model_, check)) throw ExitError(kExitCheckFailed, *message);
  };
  const auto t0 = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f) {
    backend_->step_frame();
    ++frame_;
    ++stepped_;
    stop_if_diverged(backend_->take_checks(false));
  }
  stop_if_diverged(backend_->take_checks(true));
  wall_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> Session::positions() {
  Current current(context_.get());
  const ClothSnapshot s = backend_->snapshot();
  std::vector<double> xyz;
  xyz.reserve(3 * s.pos.size());
  for (const glm::dvec4& p : s.pos) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return xyz;
}

std::vector<double> Session::velocities() {
  Current current(context_.get());
  const ClothSnapshot s = backend_->snapshot();
  const double dt = scene_.dt();
  std::vector<double> v;
  v.reserve(3 * s.disp.size());
  for (const glm::dvec4& d : s.disp) v.insert(v.end(), {d.x / dt, d.y / dt, d.z / dt});
  return v;
}

void Session::set_positions(const std::vector<double>& xyz) {
  if (xyz.size() != 3 * size_t(model_->count()))
    throw ExitError(kExitBadInput, fmt::format("set_positions: expected an array of shape ({}, 3), got {} values",
                                               model_->count(), xyz.size()));
  Current current(context_.get());
  // Through the state a checkpoint saves, so both backends take it the same way: the
  // positions in the backend's scalar, the inverse masses and displacements as they were.
  SavedState saved = backend_->save_state();
  const int bytes = saved.scalar_bytes;
  for (size_t i = 0; i < size_t(model_->count()); ++i)
    for (size_t c = 0; c < 3; ++c) {
      uint8_t* at = saved.positions.data() + (4 * i + c) * size_t(bytes);
      if (bytes == 4) {
        const float v = float(xyz[3 * i + c]);
        std::memcpy(at, &v, 4);
      } else {
        std::memcpy(at, &xyz[3 * i + c], 8);
      }
    }
  backend_->load_state(saved);
}

nlohmann::json Session::stats() {
  Current current(context_.get());
  nlohmann::json j = stats_json(scene_, *model_, *backend_, stepped_, wall_);
  j["frame"] = frame_;
  return j;
}

void Session::export_obj(const std::string& path) {
  if (export_kind(path) != ExportKind::Obj)
    throw ExitError(kExitBadInput, fmt::format("export {}: expected a file name ending in .obj (the cloth as it is now)", path));
  OutputPlan plan;
  plan.file("export", path);
  check_outputs(plan);
  Current current(context_.get());
  try {
    write_obj(path, *model_, backend_->snapshot());
  } catch (const std::runtime_error& e) {
    throw ExitError(kExitBadInput, fmt::format("export {}", e.what()));
  }
}

void Session::render(const std::string& path, const std::string& shader_name, int width, int height) {
  const auto shader = parse_shader(shader_name);
  if (!shader)
    throw ExitError(kExitBadInput, fmt::format("render: shader {}: expected one of Wireframe, Normal, Diffuse, Phong, "
                                               "Texture, Bump, Displacement, Mirror", shader_name));
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw ExitError(kExitBadInput, fmt::format("render: size ({}, {}): each side must be in [16, 8192]", width, height));
  if (std::filesystem::path(path).extension() != ".png")
    throw ExitError(kExitBadInput, fmt::format("render {}: expected a file name ending in .png", path));
  OutputPlan plan;
  plan.file("render", path);
  check_outputs(plan);
  if (!context_) context_ = require_headless_context();  // the CPU backend draws through one too
  Current current(context_.get());
  const auto root = find_project_root();
  if (!renderer_) renderer_ = std::make_unique<Renderer>(root, scene_, *model_);
  gl::RenderTarget target(width, height, 4);
  Appearance look;
  look.shader = *shader;
  const OrbitCamera camera = default_camera(scene_, *model_, float(width) / float(height));
  target.bind();
  if (auto* gpu = dynamic_cast<GpuBackend*>(backend_.get())) {
    renderer_->place_colliders(gpu->simulator().constants());
    renderer_->draw(gpu->simulator().state().positions(), gpu->simulator().state().normals(), camera, look);
  } else {
    auto* cpu = static_cast<CpuBackend<double>*>(backend_.get());
    const ClothSnapshot s = cpu->snapshot();
    const std::vector<glm::vec4> p(s.pos.begin(), s.pos.end()), n(s.normal.begin(), s.normal.end());
    gl::Buffer positions{"cpu positions"}, normals{"cpu normals"};
    gl::upload_vector(positions, p);
    gl::upload_vector(normals, n);
    renderer_->place_colliders(cpu->constants());
    renderer_->draw(positions, normals, camera, look);
  }
  write_png(path, width, height, target.read_rgba());
}

}  // namespace clothsim

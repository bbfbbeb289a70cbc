// The simulator's transfers and live edits: explicit uploads and read-backs (export,
// validation, tests), parameter changes and the viewer's grab. None runs during a step.
#include "gpu_simulator.hpp"

namespace clothsim {

void GpuSimulator::upload_colliders() {
  auto v4 = [](const Vec3<float>& v, float w) { return glm::vec4(v.x, v.y, v.z, w); };
  std::vector<layout::SphereCollider> spheres;
  for (auto& s : constants_.spheres) spheres.push_back({v4(s.origin, s.radius), {s.keep, 0.f, 0.f, 0.f}});
  std::vector<layout::PlaneCollider> planes;
  for (auto& p : constants_.planes) planes.push_back({v4(p.point, 0.f), v4(p.normal, p.keep)});
  // A storage buffer may not be empty when bound: keep one dummy element for zero colliders.
  if (spheres.empty()) spheres.resize(1);
  if (planes.empty()) planes.resize(1);
  gl::upload_vector(spheres_, spheres, GL_STATIC_DRAW);
  gl::upload_vector(planes_, planes, GL_STATIC_DRAW);
  spheres_view_.attach(spheres_, GL_RGBA32F);
  planes_view_.attach(planes_, GL_RGBA32F);
}

void GpuSimulator::set_parameters(const Scene& scene) {
  const float old_mass = constants_.mass;
  constants_ = make_constants<float>(scene, model_);
  inverse_mass_ = float(1.0 / particle_mass(scene.cloth));
  params_ = make_step_params(constants_, model_);
  step_params_.upload(0, sizeof(params_), &params_);
  upload_colliders();
  if (constants_.mass != old_mass) {
    // Density changed: every free particle's inverse mass follows (an edit-time read-back).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    auto pos = gl::download_vector<glm::vec4>(positions_);
    for (auto& p : pos) if (p.w != 0.f) p.w = inverse_mass_;
    positions_.upload(0, pos.size() * sizeof(glm::vec4), pos.data());
  }
}

void GpuSimulator::hold_particle(int i, const glm::vec3& position) {
  const glm::vec4 p(position, 0.f);
  // Both buffers, so the held particle has no velocity; shaders read them next substep.
  positions_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
  previous_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
}

void GpuSimulator::release_particle(int i) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glm::vec4 p;
  positions_.download(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
  p.w = model_.pinned[i] ? 0.f : inverse_mass_;
  positions_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
}

void GpuSimulator::reset() {
  State<float> s = initial_state<float>(model_);
  for (auto& p : s.pos) if (p.w != 0.f) p.w = inverse_mass_;
  s.prev = s.pos;
  upload(s);
  compute_normals();
  guard_.restart(s.pos, 0);
}

void GpuSimulator::download_hash(SpatialHash& h) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // a read-back, not part of a step
  h.table_size = table_size_;
  h.count = gl::download_vector<uint32_t>(cell_count_);
  h.start = gl::download_vector<uint32_t>(cell_start_);
  h.entries = gl::download_vector<uint32_t>(cell_entries_);
}

void GpuSimulator::upload(const State<float>& s) {
  gl::upload_vector(positions_, s.pos);
  gl::upload_vector(previous_, s.prev);
  if (s.force.size() == s.pos.size()) gl::upload_vector(forces_, s.force);
  // The Jacobi/ping-pong output matches the buffer it stands in for.
  positions_out_.allocate(positions_.size());
  attach_views();
}

void GpuSimulator::download(State<float>& s) {
  // Shader writes must be visible to glGetBufferSubData.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  s.pos = gl::download_vector<Vec4<float>>(positions_);
  s.prev = gl::download_vector<Vec4<float>>(previous_);
  s.force = gl::download_vector<Vec4<float>>(forces_);
  s.normal = gl::download_vector<Vec4<float>>(normals_);
}

// A checkpoint is the two state buffers as they are, read back and uploaded bit for bit.
SavedState GpuBackend::save_state() {
  State<float> s;
  sim_->download(s);
  return save_streams(s, sim_->divergence().frame(), time_);
}

void GpuBackend::load_state(const SavedState& saved) {
  State<float> s;
  sim_->download(s);  // for the inverse masses of this scene
  load_streams(saved, s);
  sim_->upload(s);
  sim_->compute_normals();
  sim_->divergence().restart(s.pos, int(saved.frame));
  time_ = saved.time;
}

}  // namespace clothsim

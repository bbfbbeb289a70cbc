// Live edits from the viewer: parameter changes, the grab, reset. None runs during a step;
// each changes buffers the next step reads.
#include "gpu_simulator.hpp"
#include "sdf_texels.hpp"

#include <utility>

#include <fmt/format.h>

namespace clothsim {

namespace {

// A collider array as it is (a storage buffer may not be empty when bound: one dummy element
// for none): in place when its size holds (moving colliders, every substep; the views stay
// attached), else made again. True when made again.
template <class T> bool upload_array(gl::Buffer& buffer, const std::vector<T>& items) {
  const std::vector<T> dummy(1);
  const std::vector<T>& v = items.empty() ? dummy : items;
  const size_t bytes = v.size() * sizeof(T);
  if (buffer.size() == bytes) {
    buffer.upload(0, bytes, v.data());
    return false;
  }
  gl::upload_vector(buffer, v, GL_DYNAMIC_DRAW);
  return true;
}

}  // namespace

void GpuSimulator::upload_colliders() {
  // The fields never change during a run: uploaded when the constants bring another set.
  const std::vector<float>* sdf = constants_.sdf.get();
  if (sdf != sdf_source_ || sdf_.size() == 0) {
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &limit);
    if (sdf != nullptr && sdf->size() > size_t(limit))
      throw SceneError(fmt::format("the mesh colliders' fields have {} nodes in all, more than this GPU's texel buffers "
                                   "hold ({}): set a larger mesh.voxel_size",
                                   sdf->size(), limit));
    const std::vector<glm::vec4> texels = sdf != nullptr && !sdf->empty() ? sdf_cell_texels(*sdf, constants_.meshes)
                                                                         : std::vector<glm::vec4>(1, glm::vec4(0.f));
    gl::upload_vector(sdf_, texels, GL_STATIC_DRAW);
    sdf_view_.attach(sdf_, GL_RGBA32F);
    sdf_source_ = sdf;
    sdf_slopes_.clear();
  }
  // Each field's slope bound, measured once per set of fields (the contact list's bound, which
  // the reference does not read): kept in the colliders' own bound.x.
  if (sdf_slopes_.size() != constants_.meshes.size())
    sdf_slopes_ = sdf != nullptr ? sdf_slopes(*sdf, constants_.meshes) : std::vector<float>(constants_.meshes.size(), 1e30f);
  for (size_t k = 0; k < constants_.meshes.size(); ++k) constants_.meshes[k].bound.x = sdf_slopes_[k];
  // Control<float>'s arrays are the GPU's structs: uploaded as they are.
  if (upload_array(meshes_, constants_.meshes)) {
    meshes_view_.attach(meshes_, GL_RGBA32F);
    meshes_int_view_.attach(meshes_, GL_RGBA32I);
  }
  if (upload_array(spheres_, constants_.spheres)) spheres_view_.attach(spheres_, GL_RGBA32F);
  if (upload_array(planes_, constants_.planes)) planes_view_.attach(planes_, GL_RGBA32F);
}

void GpuSimulator::upload_anchors() {
  std::vector<glm::vec4> anchors(constants_.anchors.begin(), constants_.anchors.end());
  if (anchors.empty()) anchors.resize(1);
  gl::upload_vector(anchors_, anchors, GL_STATIC_DRAW);
}

void GpuSimulator::apply_substep_time() {
  set_substep_time(constants_, time_);  // the Control part and the block's pin_offset, gust_phase
  step_params_.upload(0, sizeof(layout::StepParams), &constants_.params());
  upload_colliders();
}

void GpuSimulator::set_time(double t) {
  time_ = t;
  if (constants_.timeline.moves()) apply_substep_time();
}

void GpuSimulator::set_parameters(const Scene& scene) {
  const std::vector<float> old_mass = constants_.mass;
  const bool had_anchors = constants_.moving_pins(), had_wind = constants_.wind_enabled;
  const bool had_bounded = constants_.bounded_contact;
  // xpbd's carried multipliers hold the springs' forces: a switch of solver or of a spring type
  // makes them meaningless, so they start over from zero (as at the start of a run).
  auto springs_in_play = [](const Constants<float>& c) {
    std::vector<int> v{int(c.xpbd), int(c.multigrid)};  // multigrid leaves the multipliers stale
    for (const auto& m : c.materials) v.insert(v.end(), {m.enabled[0], m.enabled[1], m.enabled[2]});
    return v;
  };
  const std::vector<int> had_springs = springs_in_play(constants_);
  constants_ = make_constants<float>(scene, model_, constants_.hierarchy);  // the hierarchy kept while ks is
  masses_ = particle_masses(scene, model_);
  if (constants_.timeline.moves()) set_substep_time(constants_, time_);
  if (constants_.moving_pins() != had_anchors) upload_anchors();
  if (bool(constants_.bounded_contact) != had_bounded) upload_rest_positions();  // switched solver or self-collision
  if (bool(constants_.wind_enabled) != had_wind)
    wind_forces_.allocate((constants_.wind_enabled ? model_.count() : 1) * sizeof(glm::vec4));
  step_params_.upload(0, sizeof(layout::StepParams), &constants_.params());
  // Something compiled into the passes changed (a solver, the collider kinds, wind, moving
  // colliders or pins: shader_features.hpp): they are compiled again.
  if (const ShaderFeatures features = ShaderFeatures::of(constants_); features != features_) load_passes(features);
  upload_colliders();
  upload_materials();  // stiffness, damping, enabled springs and masses, all cheap
  if (constants_.mass != old_mass) {
    // Density changed: every free particle's inverse mass follows (an edit-time read-back).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    auto pos = gl::download_vector<glm::vec4>(positions_);
    const std::vector<float> inverse = inverse_masses();
    for (size_t i = 0; i < pos.size(); ++i) if (pos[i].w != 0.f) pos[i].w = inverse[i];
    positions_.upload(0, pos.size() * sizeof(glm::vec4), pos.data());
  }
  if (springs_in_play(constants_) != had_springs) upload_multipliers({});
  if (scene.dt() != dt_) {
    // A new substep length: the displacement per substep scales with it, so the cloth keeps
    // its velocity, and the multipliers (forces times dt^2) with its square, so the springs
    // keep their forces (the same function the reference uses, so both sides round alike).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    State<float> s;
    s.disp = download_displacement();
    s.lambda = gl::download_vector<Vec4<float>>(multipliers_);
    rescale_displacement(s, scene.dt() / dt_);
    gl::upload_vector(displacement_, s.disp);
    displacement_view_.attach(displacement_, GL_RGBA32F);
    upload_multipliers(std::move(s.lambda));
    dt_ = scene.dt();
  }
}

std::vector<float> GpuSimulator::inverse_masses() const {
  // As initial_state forms them, from the masses in double, for the current densities.
  std::vector<float> w;
  for (double m : masses_) w.push_back(float(1.0 / m));
  return w;
}

void GpuSimulator::hold_particle(int i, const glm::vec3& position) {
  const glm::vec4 p(position, 0.f), at_rest(0.f);
  // Both buffers, so the held particle has no velocity; shaders read them next substep.
  positions_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
  displacement_.upload(size_t(i) * sizeof(glm::vec4), sizeof(at_rest), &at_rest);
}

void GpuSimulator::release_particle(int i) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glm::vec4 p;
  positions_.download(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
  p.w = model_.pinned[i] ? 0.f : inverse_masses()[size_t(i)];
  positions_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
}

void GpuSimulator::reset() {
  set_time(0);
  State<float> s = initial_state<float>(model_);
  const std::vector<float> inverse = inverse_masses();
  for (size_t i = 0; i < s.pos.size(); ++i) if (s.pos[i].w != 0.f) s.pos[i].w = inverse[i];
  upload(s);
  run(PassId::compute_normals);
  guard_.restart(s.pos, 0);
}

}  // namespace clothsim

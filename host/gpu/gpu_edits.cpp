// Live edits from the viewer: parameter changes, the grab, reset. None runs during a step;
// each changes buffers the next step reads.
#include "gpu_simulator.hpp"

#include <utility>

#include <fmt/format.h>

namespace clothsim {

void GpuSimulator::apply_substep_time() {
  set_substep_time(constants_, time_);  // constants_.control, nothing else
  state_.upload_control(constants_);  // its block and the colliders; the parameter block stays
}

void GpuSimulator::set_time(double t) {
  time_ = t;
  if (constants_.timeline.moves()) apply_substep_time();
}

void GpuSimulator::set_parameters(const Scene& scene) {
  const std::vector<float> old_mass = constants_.mass;
  const bool had_anchors = constants_.moving_pins(), had_wind = constants_.wind_enabled;
  const bool had_bounded = constants_.bounded_contact;
  constants_ = make_constants<float>(scene, state_.model_, constants_.hierarchy);  // the hierarchy kept while ks is
  masses_ = particle_masses(scene, state_.model_);
  if (constants_.timeline.moves()) set_substep_time(constants_, time_);
  if (constants_.moving_pins() != had_anchors) state_.upload_anchors(constants_);
  if (bool(constants_.bounded_contact) != had_bounded) state_.upload_rest_positions(constants_);  // switched solver or self-collision
  if (bool(constants_.wind_enabled) != had_wind)
    state_.wind_forces_.allocate((constants_.wind_enabled ? state_.model_.count() : 1) * sizeof(glm::vec4));
  state_.step_params_.upload(0, sizeof(layout::StepParams), &constants_.params());
  // Something compiled into the passes changed (a solver, the collider kinds, wind, moving
  // colliders or pins: shader_features.hpp): they are compiled again.
  if (const ShaderFeatures features = ShaderFeatures::of(constants_); features != passes_.features_) passes_.load_passes(features);
  state_.upload_control(constants_);
  state_.upload_materials(constants_);  // stiffness, damping, enabled springs and masses, all cheap
  if (constants_.mass != old_mass) {
    // Density changed: every free particle's inverse mass follows (an edit-time read-back).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    auto pos = gl::download_vector<glm::vec4>(state_.positions_);
    const std::vector<float> inverse = inverse_masses();
    for (size_t i = 0; i < pos.size(); ++i) if (pos[i].w != 0.f) pos[i].w = inverse[i];
    state_.positions_.upload(0, pos.size() * sizeof(glm::vec4), pos.data());
  }
  if (scene.dt() != dt_) {
    // A new substep length: the displacement per substep scales with it, so the cloth keeps
    // its velocity (the same function the reference uses, so both sides round alike).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    State<float> s;
    s.disp = state_.download_displacement();
    rescale_displacement(s, scene.dt() / dt_);
    gl::upload_vector(state_.displacement_, s.disp);
    state_.displacement_view_.attach(state_.displacement_, GL_RGBA32F);
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
  state_.positions_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
  state_.displacement_.upload(size_t(i) * sizeof(glm::vec4), sizeof(at_rest), &at_rest);
}

void GpuSimulator::release_particle(int i) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glm::vec4 p;
  state_.positions_.download(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
  p.w = state_.model_.pinned[i] ? 0.f : inverse_masses()[size_t(i)];
  state_.positions_.upload(size_t(i) * sizeof(glm::vec4), sizeof(p), &p);
}

void GpuSimulator::reset() {
  set_time(0);
  State<float> s = initial_state<float>(state_.model_);
  const std::vector<float> inverse = inverse_masses();
  for (size_t i = 0; i < s.pos.size(); ++i) if (s.pos[i].w != 0.f) s.pos[i].w = inverse[i];
  upload(s);
  run(PassId::compute_normals);
  passes_.guard_.restart(s.pos, 0);
}

}  // namespace clothsim

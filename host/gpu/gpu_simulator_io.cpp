// The simulator's transfers: explicit uploads and read-backs for export, validation, the pass
// checks and tests. None runs during a step.
#include "gpu_simulator.hpp"
#include "gpu_multigrid.hpp"

namespace clothsim {

void GpuSimulator::upload(const State<float>& s) {
  gl::upload_vector(state_.positions_, s.pos);
  gl::upload_vector(state_.displacement_, s.disp);
  if (s.force.size() == s.pos.size()) gl::upload_vector(state_.forces_, s.force);
  if (constants_.wind_enabled && s.wind.size() == s.pos.size()) gl::upload_vector(state_.wind_forces_, s.wind);
  // The multigrid solve's offsets, which fabric's predict reads from the substep before
  // (solve_start_offset): the state's, or zero for a state without them (as the reference starts).
  if (state_.multigrid_) {
    gl::Buffer& offset = state_.multigrid_->offset;
    if (s.offset.size() == s.pos.size())
      offset.upload(0, s.offset.size() * sizeof(glm::vec4), s.offset.data());
    else
      offset.clear_to_zero();
  }
  // The skinned colliders' nearest triangles, where the state has them (each substep's first
  // collision rebuilds them before any pass reads them: a pass check runs later passes alone);
  // the far records and the summed moves after them void (compute/nearest.glsl): they hold only
  // for the run that made them.
  if (constants_.skin_meshes > 0 && state_.nearest_.size() == state_.nearest_words() * sizeof(uint32_t)) {
    const size_t slots = state_.nearest_slots_ * sizeof(uint32_t);
    if (s.nearest.size() == state_.nearest_slots_) state_.nearest_.upload(0, slots, s.nearest.data());
    const std::vector<uint32_t> zero(state_.nearest_words() - state_.nearest_slots_, 0u);
    state_.nearest_.upload(slots, zero.size() * sizeof(uint32_t), zero.data());
  }
  // The Jacobi/ping-pong output matches the buffer it stands in for.
  state_.positions_out_.allocate(state_.positions_.size());
  state_.attach_views();
}

void GpuSimulator::download(State<float>& s) {
  // Shader writes must be visible to glGetBufferSubData.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  s.pos = gl::download_vector<Vec4<float>>(state_.positions_);
  s.disp = state_.download_displacement();
  s.force = gl::download_vector<Vec4<float>>(state_.forces_);
  s.normal = gl::download_vector<Vec4<float>>(state_.normals_);
  if (constants_.wind_enabled) s.wind = gl::download_vector<Vec4<float>>(state_.wind_forces_);
  if (state_.multigrid_) s.offset = gl::download_vector<Vec4<float>>(state_.multigrid_->offset);
  if (constants_.skin_meshes > 0) s.nearest = gl::download_vector<uint32_t>(state_.nearest_, 0, state_.nearest_slots_);
}

// A checkpoint is the two state buffers as they are, read back and uploaded bit for bit.
SavedState GpuBackend::save_state() {
  State<float> s;
  sim_->download(s);
  return save_streams(s, sim_->passes().divergence().frame(), sim_->time(), sim_->constants().timeline.dt);
}

void GpuBackend::load_state(const SavedState& saved) {
  State<float> s;
  sim_->download(s);  // for the inverse masses of this scene
  // Rescaled on the host by the reference's function when the substep length differs, so both
  // backends round alike.
  load_streams(saved, s, sim_->constants().timeline.dt);
  sim_->upload(s);
  sim_->run(PassId::compute_normals);
  sim_->passes().divergence().restart(s.pos, int(saved.frame));
  sim_->set_time(saved.time);
}

}  // namespace clothsim

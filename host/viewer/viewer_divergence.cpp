// The viewer's side of the divergence guard: a frame that fails its check pauses the viewer,
// puts the message in the panel, and brings the cloth back to the newest frame that passed,
// so the window shows a cloth instead of garbage while the user lowers ks or raises
// simulation_steps. P (or N) continues from there; R and reload start over and run.
#include "viewer_app.hpp"

namespace clothsim {

bool Viewer::poll_divergence() {
  GpuDivergenceGuard& guard = session_.sim->passes().divergence();
  for (const FrameCheck& check : guard.take(false)) {
    auto message = divergence_message(st_.scene, *session_.model, check);
    if (!message) continue;
    int frame = 0;
    const std::vector<glm::vec4> good = guard.last_good(&frame);
    State<float> state;
    state.pos = good;
    state.disp.assign(good.size(), Vec4<float>(0));  // at rest: the velocity that blew up is gone
    session_.sim->upload(state);
    // A particle held at that frame was kept with inverse mass 0: give it its own back.
    if (grab_.active()) session_.sim->release_particle(grab_.particle);
    grab_ = {};
    session_.sim->run(PassId::compute_normals);
    guard.restart(good, frame);
    st_.paused = true;
    st_.step_once = false;
    st_.divergence = fmt::format("{}\nShowing frame {}, the last one that passed. Change the parameters, then P "
                                 "to continue from it, or R to start over.",
                                 *message, frame);
    return true;
  }
  return false;
}

void Viewer::clear_divergence(bool unpause) {
  if (st_.divergence.empty()) return;
  st_.divergence.clear();
  if (unpause) st_.paused = false;
}

}  // namespace clothsim

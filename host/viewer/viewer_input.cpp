// Keys and mouse of the viewer, as the classic app: P pause, N step, R reset, Space camera,
// Esc quit; plus F1 panels and S screenshot. Left-drag orbits, right- or ctrl-drag pans, the
// wheel zooms, shift-click grabs the particle under the cursor until the button is released.
#include <fmt/format.h>

#include "viewer_app.hpp"

namespace clothsim {
namespace {
Viewer* self(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }
}  // namespace

void Viewer::install_callbacks() {
  GLFWwindow* w = window_->handle();
  glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
    if (action == GLFW_PRESS && !ImGui::GetIO().WantCaptureKeyboard) self(win)->on_key(key, mods);
  });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int mods) {
    self(win)->on_mouse_button(button, action, mods);
  });
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) { self(win)->on_cursor(x, y); });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
    if (!ImGui::GetIO().WantCaptureMouse) self(win)->st_.camera.zoom(float(dy));
  });
}

void Viewer::on_key(int key, int) {
  switch (key) {
    case GLFW_KEY_P: clear_divergence(false); st_.paused = !st_.paused; break;
    case GLFW_KEY_N: clear_divergence(false); if (st_.paused) st_.step_once = true; break;
    case GLFW_KEY_R: clear_divergence(true); session_.sim->reset(); grab_ = {}; break;
    case GLFW_KEY_SPACE: reset_camera(); break;
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_->handle(), GLFW_TRUE); break;
    case GLFW_KEY_F1: st_.show_panels = !st_.show_panels; break;
    case GLFW_KEY_S: save_screenshot(fmt::format("clothsim_{}_{:03d}.png", st_.scene.name(), screenshots_++)); break;
    default: break;
  }
}

void Viewer::on_mouse_button(int button, int action, int mods) {
  if (action == GLFW_RELEASE) {
    if (grab_.active()) session_.sim->release_particle(grab_.particle);
    grab_ = {};
    drag_button_ = -1;
    return;
  }
  if (ImGui::GetIO().WantCaptureMouse) return;
  if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT)) {
    // Picking reads the cloth back once, at click time only.
    int w = 0, h = 0;
    glfwGetWindowSize(window_->handle(), &w, &h);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const auto pos = gl::download_vector<glm::vec4>(session_.sim->positions());
    const Ray ray = pick_ray(st_.camera, glm::vec2(cursor_), glm::vec2(w, h));
    if (auto i = pick_particle(ray, pos, *session_.model)) {
      grab_ = begin_grab(*i, glm::vec3(pos[*i]), st_.camera);
      grab_target_ = grab_.plane_point;
      session_.sim->hold_particle(*i, grab_target_);
    }
    return;
  }
  drag_button_ = button;
  drag_pan_ = button == GLFW_MOUSE_BUTTON_RIGHT || (mods & GLFW_MOD_CONTROL);
}

void Viewer::on_cursor(double x, double y) {
  const glm::dvec2 now(x, y), delta = now - cursor_;
  cursor_ = now;
  int w = 0, h = 0;
  glfwGetWindowSize(window_->handle(), &w, &h);
  if (grab_.active()) {
    grab_target_ = grab_.target(pick_ray(st_.camera, glm::vec2(now), glm::vec2(w, h)));
    session_.sim->hold_particle(grab_.particle, grab_target_);  // visible even while paused
    return;
  }
  if (drag_button_ < 0) return;
  if (drag_pan_) st_.camera.pan(float(delta.x), float(delta.y), float(h));
  else st_.camera.orbit(float(delta.x), float(delta.y));
}

}  // namespace clothsim

// Keys and mouse of the viewer, as the classic app: P pause, N step, R reset, Space camera,
// Esc quit; plus F1 panels and S screenshot. Left-drag orbits, right- or ctrl-drag pans, the
// wheel zooms, shift-click grabs the particle under the cursor until the button is released,
// alt-click drags the sphere or mesh collider under it (origin and keyframes, applied live).
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "colliders/mesh_collider.hpp"
#include "viewer_app.hpp"

namespace clothsim {
namespace {
Viewer* self(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

// The sphere whose surface the ray meets first, and where. Taken from the simulation's
// constants, where a keyframed sphere is now (the scene's origin is only its static value).
std::optional<std::pair<int, glm::vec3>> pick_sphere(const Ray& ray, const std::vector<layout::SphereCollider>& spheres) {
  std::optional<std::pair<int, glm::vec3>> best;
  float best_t = INFINITY;
  for (size_t k = 0; k < spheres.size(); ++k) {
    const glm::vec3 oc = ray.origin - glm::vec3(spheres[k].origin_radius);
    const float b = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - spheres[k].origin_radius.w * spheres[k].origin_radius.w;
    const float disc = b * b - c;
    if (disc < 0.f) continue;
    const float t = -b - std::sqrt(disc);
    if (t > 0.f && t < best_t) {
      best_t = t;
      best = std::pair{int(k), ray.origin + ray.direction * t};
    }
  }
  return best;
}
// The mesh collider whose surface the ray meets first (Moeller-Trumbore over its triangles,
// placed where the simulation has it now), and where: as pick_sphere, at click time only.
std::optional<std::pair<int, glm::vec3>> pick_mesh(const Ray& ray, const Scene& scene,
                                                   const std::vector<layout::MeshCollider>& meshes, float best_t) {
  std::optional<std::pair<int, glm::vec3>> best;
  for (size_t k = 0; k < meshes.size() && k < scene.meshes.size(); ++k) {
    const SurfaceMesh& surface = load_collider_mesh(scene, k)->surface;
    const glm::mat3 rot(collider_rotation(scene.meshes[k]));
    const glm::vec3 origin = mesh_origin(meshes[k]);
    for (const glm::uvec3& t : surface.triangles) {
      const glm::vec3 a = rot * glm::vec3(surface.positions[t[0]]) + origin;
      const glm::vec3 e1 = rot * glm::vec3(surface.positions[t[1]]) + origin - a;
      const glm::vec3 e2 = rot * glm::vec3(surface.positions[t[2]]) + origin - a;
      const glm::vec3 p = glm::cross(ray.direction, e2);
      const float det = glm::dot(e1, p);
      if (std::abs(det) < 1e-12f) continue;
      const glm::vec3 s = ray.origin - a;
      const float u = glm::dot(s, p) / det;
      const glm::vec3 q = glm::cross(s, e1);
      const float v = glm::dot(ray.direction, q) / det, d = glm::dot(e2, q) / det;
      if (u < 0.f || v < 0.f || u + v > 1.f || !(d > 0.f) || d >= best_t) continue;
      best_t = d;
      best = std::pair{int(k), ray.origin + ray.direction * d};
    }
  }
  return best;
}

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
    sphere_drag_ = {};
    drag_button_ = -1;
    return;
  }
  if (ImGui::GetIO().WantCaptureMouse) return;
  if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT)) {
    // Picking reads the cloth back once, at click time only.
    int w = 0, h = 0;
    glfwGetWindowSize(window_->handle(), &w, &h);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const auto pos = gl::download_vector<glm::vec4>(session_.sim->state().positions());
    const Ray ray = pick_ray(st_.camera, glm::vec2(cursor_), glm::vec2(w, h));
    if (auto i = pick_particle(ray, pos, *session_.model)) {
      grab_ = begin_grab(*i, glm::vec3(pos[*i]), st_.camera);
      grab_target_ = grab_.plane_point;
      session_.sim->hold_particle(*i, grab_target_);
    }
    return;
  }
  if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_ALT)) {
    int w = 0, h = 0;
    glfwGetWindowSize(window_->handle(), &w, &h);
    const Ray ray = pick_ray(st_.camera, glm::vec2(cursor_), glm::vec2(w, h));
    const auto sphere = pick_sphere(ray, session_.sim->constants().control.spheres);
    const float sphere_t = sphere ? glm::length(sphere->second - ray.origin) : INFINITY;
    if (auto mesh = pick_mesh(ray, st_.scene, session_.sim->constants().control.meshes, sphere_t))
      sphere_drag_ = {mesh->first, begin_grab(0, mesh->second, st_.camera), mesh->second, glm::dvec3(0.0), true};
    else if (sphere)
      sphere_drag_ = {sphere->first, begin_grab(0, sphere->second, st_.camera), sphere->second, glm::dvec3(0.0)};
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
  if (sphere_drag_.sphere >= 0) {
    // The whole path moves with the sphere, so a keyframed one keeps its motion.
    const glm::dvec3 delta = glm::dvec3(sphere_drag_.plane.target(pick_ray(st_.camera, glm::vec2(now), glm::vec2(w, h))) -
                                        sphere_drag_.start);
    auto shift = [&](glm::dvec3& origin, std::optional<MotionParams>& motion) {
      origin += delta - sphere_drag_.moved;
      if (motion)
        for (Keyframe& k : motion->keyframes) k.value += delta - sphere_drag_.moved;
    };
    if (sphere_drag_.mesh) {
      MeshColliderParams& m = st_.scene.meshes[size_t(sphere_drag_.sphere)];
      shift(m.origin, m.motion);
    } else {
      SphereParams& s = st_.scene.spheres[size_t(sphere_drag_.sphere)];
      shift(s.origin, s.motion);
    }
    sphere_drag_.moved = delta;
    st_.parameters_changed = true;  // set_parameters uploads the colliders before the next step
    return;
  }
  if (drag_button_ < 0) return;
  if (drag_pan_) st_.camera.pan(float(delta.x), float(delta.y), float(h));
  else st_.camera.orbit(float(delta.x), float(delta.y));
}

}  // namespace clothsim

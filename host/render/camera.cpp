#include "camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace clothsim {

glm::vec3 OrbitCamera::eye() const {
  const glm::vec3 dir(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  return target + dir * distance;
}

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), target, glm::vec3(0, 1, 0)); }

glm::mat4 OrbitCamera::projection() const {
  return glm::perspective(fov_y, aspect, std::max(distance * 0.01f, 1e-3f), distance * 100.f);
}

void OrbitCamera::orbit(float dx, float dy) {
  yaw -= dx * 0.005f;
  // Stay short of the poles, where lookAt's up vector degenerates.
  pitch = std::clamp(pitch + dy * 0.005f, -1.55f, 1.55f);
}

void OrbitCamera::pan(float dx, float dy, float height) {
  // One pixel moves the target by the size of a pixel at the target's depth.
  const float metres_per_pixel = 2.f * distance * std::tan(fov_y / 2) / std::max(height, 1.f);
  const glm::mat4 v = view();
  const glm::vec3 right(v[0][0], v[1][0], v[2][0]), up(v[0][1], v[1][1], v[2][1]);
  target += (-dx * right + dy * up) * metres_per_pixel;
}

void OrbitCamera::zoom(float steps) { distance = std::clamp(distance * std::pow(0.9f, steps), 1e-3f, 1e4f); }

void OrbitCamera::look_from(const glm::vec3& e, const glm::vec3& t) {
  target = t;
  const glm::vec3 d = e - t;
  distance = std::max(glm::length(d), 1e-3f);
  pitch = std::asin(std::clamp(d.y / distance, -1.f, 1.f));
  yaw = std::atan2(d.x, d.z);
}

OrbitCamera default_camera(const Scene& scene, const ClothModel& model, float aspect) {
  glm::dvec3 lo(1e300), hi(-1e300);
  auto add = [&](glm::dvec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); };
  for (auto& p : model.initial) add(p);
  const double size = std::max(scene.cloth.width, scene.cloth.height);
  // A pinned cloth hangs below its pins; an unpinned one falls onto whatever is below.
  if (!scene.cloth.pinned.empty()) add(glm::dvec3(lo.x, lo.y - size, lo.z));
  for (auto& s : scene.spheres) { add(s.origin - glm::dvec3(s.radius)); add(s.origin + glm::dvec3(s.radius)); }
  for (auto& pl : scene.planes) {
    for (auto& p : model.initial) add(p - pl.normal * glm::dot(p - pl.point, pl.normal));
  }
  OrbitCamera cam;
  cam.aspect = aspect;
  cam.target = glm::vec3((lo + hi) * 0.5);
  const float radius = float(glm::length(hi - lo) * 0.5);
  const float half_fov = std::min(cam.fov_y, 2.f * std::atan(std::tan(cam.fov_y / 2) * aspect)) / 2;
  // The bounding sphere of a box is loose for a flat cloth: 0.95 of it still frames everything.
  cam.distance = radius / std::sin(half_fov) * 0.95f;
  return cam;
}

}  // namespace clothsim

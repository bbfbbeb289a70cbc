#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

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

// Roughly where each particle comes to rest, for framing (no simulation): a pinned cloth hangs
// straight down from the nearest point of its pins' box, by its distance from that point; an
// unpinned one drapes the same way from the top of a sphere below it, or else falls until a
// plane stops it; nothing hangs through a plane. With nothing to stop it, or no gravity, a
// particle is framed where it starts.
std::vector<glm::dvec3> resting_points(const Scene& scene, const ClothModel& model) {
  const glm::dvec3 g = scene.simulation.gravity;
  if (glm::length(g) == 0) return model.initial;
  const glm::dvec3 down = glm::normalize(g);
  auto across = [&](glm::dvec3 v) { return v - down * glm::dot(v, down); };
  glm::dvec3 pin_lo(1e300), pin_hi(-1e300);
  for (size_t i = 0; i < model.initial.size(); ++i)
    if (model.pinned[i]) {
      pin_lo = glm::min(pin_lo, model.initial[i]);
      pin_hi = glm::max(pin_hi, model.initial[i]);
    }
  const bool pinned = pin_lo.x <= pin_hi.x;
  std::vector<glm::dvec3> tops;  // of the spheres the cloth starts above
  for (auto& s : scene.spheres) {
    const glm::dvec3 top = s.origin - down * s.radius;
    for (auto& p : model.initial)
      if (glm::length(across(p - s.origin)) < s.radius && glm::dot(p - top, down) < 0) {
        tops.push_back(top);
        break;
      }
  }
  std::vector<glm::dvec3> out;
  for (auto& p : model.initial) {
    glm::dvec3 r = p;
    if (pinned) {
      const glm::dvec3 q = glm::clamp(p, pin_lo, pin_hi);
      r = q + down * glm::length(p - q);
    } else if (!tops.empty()) {
      auto flat_distance = [&](const glm::dvec3& t) { return glm::length(across(p - t)); };
      const glm::dvec3 t = *std::min_element(tops.begin(), tops.end(), [&](auto& a, auto& b) {
        return flat_distance(a) < flat_distance(b);
      });
      r = t + down * flat_distance(t);
    } else {
      double fall = 1e300;  // to the first plane below
      for (auto& pl : scene.planes) {
        const double rate = glm::dot(down, pl.normal);  // how fast falling closes in on the plane
        if (rate == 0) continue;
        const double t = -glm::dot(p - pl.point, pl.normal) / rate;
        if (t > 0) fall = std::min(fall, t);
      }
      if (fall < 1e300) r = p + down * fall;
    }
    for (auto& pl : scene.planes) {
      const double start = glm::dot(p - pl.point, pl.normal), now = glm::dot(r - pl.point, pl.normal);
      if (start * now < 0) r -= pl.normal * now;
    }
    out.push_back(r);
  }
  return out;
}

OrbitCamera default_camera(const Scene& scene, const ClothModel& model, float aspect) {
  glm::dvec3 lo(1e300), hi(-1e300);
  auto add = [&](glm::dvec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); };
  // Where the cloth starts and where it will rest, so a whole run stays in view.
  for (auto& p : model.initial) add(p);
  for (auto& p : resting_points(scene, model)) add(p);
  for (auto& s : scene.spheres) { add(s.origin - glm::dvec3(s.radius)); add(s.origin + glm::dvec3(s.radius)); }
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

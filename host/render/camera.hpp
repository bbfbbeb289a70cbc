// Cameras: an orbit camera (target, distance, yaw, pitch) whose orbit/pan/zoom maths the
// viewer uses, and the default framing of a scene.
#pragma once

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "cloth/cloth.hpp"
#include "scene/scene.hpp"

namespace clothsim {

struct OrbitCamera {
  glm::vec3 target{0.5f, 0.5f, 0.5f};
  float distance = 2.5f;
  float yaw = 0.6f;    // radians about +y, 0 looks along -z
  float pitch = 0.45f; // radians above the horizon
  float fov_y = 0.7854f;  // 45 degrees
  float aspect = 4.f / 3.f;

  glm::vec3 eye() const;
  glm::mat4 view() const;
  glm::mat4 projection() const;
  glm::mat4 view_projection() const { return projection() * view(); }

  // Mouse-driven motion, in screen pixels of a window `height` pixels tall.
  void orbit(float dx_pixels, float dy_pixels);
  void pan(float dx_pixels, float dy_pixels, float height);
  void zoom(float scroll_steps);  // > 0 moves closer
  // Places the eye explicitly (the --camera option).
  void look_from(const glm::vec3& eye, const glm::vec3& target);
};

// A camera that frames the cloth where it starts and where it will come to rest (hanging below
// its pins, draped over a sphere, lying on a plane), and the spheres, from the front and a
// little above, like the classic viewer.
OrbitCamera default_camera(const Scene& scene, const ClothModel& model, float aspect);

// Roughly where each particle comes to rest, for framing (no simulation; camera.cpp says how).
std::vector<glm::dvec3> resting_points(const Scene& scene, const ClothModel& model);

}  // namespace clothsim

// Mouse picking and dragging, pure maths so it is tested without a window: a ray through a
// pixel, the particle under it (ray vs the cloth's triangles, on a read-back made only at
// click time), and where a grabbed particle goes as the mouse moves (the plane through it
// facing the camera).
#pragma once

#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "camera.hpp"
#include "cloth/cloth.hpp"

namespace clothsim {

struct Ray {
  glm::vec3 origin, direction;  // direction is unit length
};

// Ray from the eye through pixel (x, y) of a viewport, y measured from the top.
Ray pick_ray(const OrbitCamera& camera, glm::vec2 pixel, glm::vec2 viewport);

// The particle nearest to where the ray first hits the cloth, or nothing.
std::optional<int> pick_particle(const Ray& ray, const std::vector<glm::vec4>& positions, const ClothModel& model);

// A particle held by the mouse: it moves in the plane through its grab point facing the camera.
struct Grab {
  int particle = -1;
  glm::vec3 plane_point{0}, plane_normal{0, 0, 1};
  bool active() const { return particle >= 0; }
  // Where the particle goes for the current mouse ray (stays put if the ray misses the plane).
  glm::vec3 target(const Ray& ray) const;
};

Grab begin_grab(int particle, const glm::vec3& position, const OrbitCamera& camera);

}  // namespace clothsim

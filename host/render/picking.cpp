#include "picking.hpp"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace clothsim {

Ray pick_ray(const OrbitCamera& camera, glm::vec2 pixel, glm::vec2 viewport) {
  const glm::vec2 ndc(2.f * pixel.x / viewport.x - 1.f, 1.f - 2.f * pixel.y / viewport.y);
  const glm::mat4 inv = glm::inverse(camera.view_projection());
  glm::vec4 near_p = inv * glm::vec4(ndc, -1.f, 1.f), far_p = inv * glm::vec4(ndc, 1.f, 1.f);
  near_p /= near_p.w;
  far_p /= far_p.w;
  return {camera.eye(), glm::normalize(glm::vec3(far_p) - glm::vec3(near_p))};
}

namespace {
// Möller–Trumbore: distance along the ray to triangle (a, b, c), or < 0 for a miss.
float hit_triangle(const Ray& r, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(r.direction, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return -1.f;
  const float inv = 1.f / det;
  const glm::vec3 s = r.origin - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.f || u > 1.f) return -1.f;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(r.direction, q) * inv;
  if (v < 0.f || u + v > 1.f) return -1.f;
  return glm::dot(e2, q) * inv;
}
}  // namespace

std::optional<int> pick_particle(const Ray& ray, const std::vector<glm::vec4>& pos, const ClothModel& model) {
  float best = std::numeric_limits<float>::infinity();
  std::optional<int> picked;
  for (const auto& t : model.triangles) {
    const glm::vec3 a(pos[t[0]]), b(pos[t[1]]), c(pos[t[2]]);
    const float d = hit_triangle(ray, a, b, c);
    if (d <= 0.f || d >= best) continue;
    best = d;
    const glm::vec3 hit = ray.origin + ray.direction * d;
    int nearest = int(t[0]);
    for (uint32_t k : t)
      if (glm::length(glm::vec3(pos[k]) - hit) < glm::length(glm::vec3(pos[nearest]) - hit)) nearest = int(k);
    picked = nearest;
  }
  return picked;
}

glm::vec3 Grab::target(const Ray& ray) const {
  const float denom = glm::dot(ray.direction, plane_normal);
  if (std::abs(denom) < 1e-6f) return plane_point;
  const float t = glm::dot(plane_point - ray.origin, plane_normal) / denom;
  return t > 0.f ? ray.origin + ray.direction * t : plane_point;
}

Grab begin_grab(int particle, const glm::vec3& position, const OrbitCamera& camera) {
  return {particle, position, glm::normalize(camera.eye() - camera.target)};
}

}  // namespace clothsim

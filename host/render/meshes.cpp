#include "meshes.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace clothsim {

MeshData sphere_mesh(const glm::vec3& c, float r, int lat, int lon) {
  MeshData m;
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= lat; ++i) {
    const float theta = pi * float(i) / float(lat);  // from the north pole
    for (int j = 0; j <= lon; ++j) {
      const float phi = 2 * pi * float(j) / float(lon);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.emplace_back(c + r * n, 1.f);
      m.normals.emplace_back(n, 0.f);
      m.extras.push_back({glm::vec4(float(j) / lon, float(i) / lat, 0, 0),
                          glm::vec4(-std::sin(phi), 0.f, std::cos(phi), 0.f)});
    }
  }
  for (int i = 0; i < lat; ++i)
    for (int j = 0; j < lon; ++j) {
      const uint32_t a = i * (lon + 1) + j, b = a + 1, d = a + lon + 1, e = d + 1;
      m.indices.insert(m.indices.end(), {a, b, d, b, e, d});
    }
  return m;
}

MeshData plane_mesh(const glm::vec3& c, const glm::vec3& n, float half) {
  MeshData m;
  // Any unit vector not parallel to n gives the first tangent.
  const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
  const glm::vec3 t = glm::normalize(helper - n * glm::dot(helper, n)), b = glm::cross(n, t);
  const float tiles = 2 * half;  // one texture repeat per metre
  for (int k = 0; k < 4; ++k) {
    const float u = (k & 1) ? 1.f : -1.f, v = (k & 2) ? 1.f : -1.f;
    m.positions.emplace_back(c + half * (u * t + v * b), 1.f);
    m.normals.emplace_back(n, 0.f);
    m.extras.push_back({glm::vec4((u + 1) * 0.5f * tiles, (v + 1) * 0.5f * tiles, 0, 0), glm::vec4(t, 0)});
  }
  m.indices = {0, 1, 2, 1, 3, 2};
  return m;
}

MeshData surface_mesh(const SurfaceMesh& surface, const glm::mat3& rotation, const glm::vec3& origin) {
  std::vector<glm::dvec3> face(surface.triangles.size()), smooth(surface.positions.size(), glm::dvec3(0.0));
  for (size_t f = 0; f < surface.triangles.size(); ++f) {
    const glm::uvec3 t = surface.triangles[f];
    const glm::dvec3 p[3] = {surface.positions[t[0]], surface.positions[t[1]], surface.positions[t[2]]};
    const glm::dvec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
    face[f] = glm::length(c) > 0 ? glm::normalize(c) : glm::dvec3(0.0);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      const double l = glm::length(e1) * glm::length(e2);
      smooth[t[k]] += face[f] * (l > 0 ? std::acos(std::clamp(glm::dot(e1, e2) / l, -1.0, 1.0)) : 0.0);
    }
  }
  MeshData m;
  const double cos30 = std::cos(30.0 * 3.14159265358979323846 / 180.0);
  for (size_t f = 0; f < surface.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = surface.triangles[f][k];
      const double len = glm::length(smooth[v]);
      const glm::dvec3 s = len > 0 ? smooth[v] / len : face[f];
      const glm::vec3 n = rotation * glm::vec3(glm::dot(s, face[f]) > cos30 ? s : face[f]);
      m.positions.emplace_back(rotation * glm::vec3(surface.positions[v]) + origin, 1.f);
      m.normals.emplace_back(n, 0.f);
      // No uv on a collider mesh: the texture shaders see one texel; a tangent across the normal.
      const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
      m.extras.push_back({glm::vec4(0.f), glm::vec4(glm::normalize(helper - n * glm::dot(helper, n)), 0.f)});
      m.indices.push_back(uint32_t(m.indices.size()));
    }
  return m;
}

std::vector<uint32_t> cloth_triangle_indices(const ClothModel& model) {
  std::vector<uint32_t> out;
  for (auto& t : model.triangles) out.insert(out.end(), t.begin(), t.end());
  return out;
}

std::vector<uint32_t> cloth_spring_indices(const ClothModel& m, SpringType type) {
  std::vector<uint32_t> out;
  for (const Spring& s : m.springs)
    if (s.type == type) out.insert(out.end(), {s.i, s.j});
  return out;
}

}  // namespace clothsim

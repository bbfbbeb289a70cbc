#include "meshes.hpp"

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

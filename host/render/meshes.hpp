// Index and vertex data for what the renderer draws, built once on the CPU.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "../../compute/layout.glsl"
#include "cloth.hpp"

namespace clothsim {

struct MeshData {
  std::vector<glm::vec4> positions, normals;   // pulled by gl_VertexID like the cloth
  std::vector<layout::MeshVertex> extras;      // uv and tangent
  std::vector<uint32_t> indices;               // triangles
};

// A UV sphere with `lat` latitude bands and `lon` longitude segments (the classic -a / -o).
MeshData sphere_mesh(const glm::vec3& centre, float radius, int lat, int lon);
// A square of half-size `half` on the plane through `centre` with unit `normal`.
MeshData plane_mesh(const glm::vec3& centre, const glm::vec3& normal, float half);

// The cloth's triangles (DESIGN.md §1), and its springs of one type as line pairs.
std::vector<uint32_t> cloth_triangle_indices(const ClothModel& model);
std::vector<uint32_t> cloth_spring_indices(const ClothModel& model, SpringType type);

}  // namespace clothsim

// Index and vertex data for what the renderer draws, built once on the CPU.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec4.hpp>

#include "../../compute/layout.glsl"
#include "cloth/cloth.hpp"
#include "colliders/sdf.hpp"

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

// A mesh collider's surface placed by `rotation` then `origin`: three vertices per triangle, each
// with the smooth (angle-weighted) normal of its vertex unless that is more than 30 degrees off
// the face's, where the face's is kept (a cube's edges stay sharp, a curved model smooth).
MeshData surface_mesh(const SurfaceMesh& surface, const glm::mat3& rotation, const glm::vec3& origin);

// The cloth's triangles (docs/design.md §1), and its springs of one type as line pairs.
std::vector<uint32_t> cloth_triangle_indices(const ClothModel& model);
std::vector<uint32_t> cloth_spring_indices(const ClothModel& model, SpringType type);

}  // namespace clothsim

// Draws the cloth straight from the simulation's storage buffers (vertex pulling by
// gl_VertexID: no copy), and the colliders, with any of the classic shaders.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera.hpp"
#include "objects.hpp"
#include "program.hpp"
#include "reference.hpp"
#include "texture.hpp"

namespace clothsim {

enum class ShaderKind { Wireframe, Normal, Diffuse, Phong, Texture, Bump, Displacement, Mirror };
inline constexpr std::array<const char*, 8> kShaderNames{"Wireframe", "Normal", "Diffuse", "Phong",
                                                         "Texture", "Bump", "Displacement", "Mirror"};
// "Phong" -> ShaderKind::Phong (case-insensitive); nullopt for an unknown name.
std::optional<ShaderKind> parse_shader(const std::string& name);

// What the user can change about the look (the viewer's Appearance panel).
struct Appearance {
  ShaderKind shader = ShaderKind::Phong;
  glm::vec4 color{0.9f, 0.88f, 0.85f, 1.f};
  float normal_scaling = 2.f;
  float height_scaling = 0.02f;  // metres at height 1
  // Scales the light before the tone map (shaders/lighting.glsl): 2 is one stop brighter.
  float exposure = 1.f;
  bool show_spheres = true;
  bool show_planes = true;
  bool show_meshes = true;
  std::array<bool, 3> wire_springs{true, true, false};  // structural, shearing, bending
};

struct RendererOptions {
  int sphere_lat = 40, sphere_lon = 40;  // the classic -a / -o
  // Spheres are drawn at 0.92 r, as the classic app did, so the cloth resting on the
  // collision surface is never hidden inside the drawn sphere.
  float sphere_shrink = 0.92f;
  gl::TextureFiltering filtering{};  // of every texture
};

class Renderer {
 public:
  Renderer(const std::filesystem::path& root, const Scene& scene, const ClothModel& model,
           const RendererOptions& options = {});
  ~Renderer();

  // Where the colliders are now: a sphere's origin, a point on each plane (their normals never
  // change), in file order. Keyframed colliders move in the simulation, so callers pass the
  // simulator's current constants before every draw; the meshes stay as built and are
  // translated (u_model) from where the scene file put them. Until called, they are drawn there.
  void place_colliders(const std::vector<glm::vec3>& sphere_origins, const std::vector<glm::vec3>& plane_points,
                       const std::vector<glm::vec3>& mesh_origins = {});
  template <class R> void place_colliders(const Constants<R>& c) {
    std::vector<glm::vec3> spheres, planes, meshes;
    for (const auto& s : c.spheres) spheres.emplace_back(s.origin);
    for (const auto& p : c.planes) planes.emplace_back(p.point);
    for (const auto& m : c.meshes) meshes.emplace_back(m.origin);
    place_colliders(spheres, planes, meshes);
  }

  // Draws into the bound framebuffer (clears it first).
  void draw(const gl::Buffer& positions, const gl::Buffer& normals, const OrbitCamera& camera,
            const Appearance& look);

  struct Mesh;  // an index buffer in a VAO, plus vertex buffers for colliders (renderer.cpp)

 private:
  // Indices [first, first + count) of the mesh (count < 0: all of them).
  void draw_mesh(const Mesh& mesh, gl::Program& program, bool lines, GLsizei first = 0, GLsizei count = -1) const;
  gl::Program& program(ShaderKind kind);

  const ClothModel& model_;
  std::filesystem::path root_;
  std::vector<std::optional<gl::Program>> programs_;  // built on first use
  std::unique_ptr<Mesh> cloth_;
  std::array<std::unique_ptr<Mesh>, 3> springs_;
  std::vector<std::unique_ptr<Mesh>> spheres_, planes_, meshes_;
  // Where each collider's mesh was built (the scene's origin / point) and where it is now.
  std::vector<glm::vec3> sphere_built_, plane_built_, sphere_now_, plane_now_, mesh_built_, mesh_now_;
  gl::Texture fabric_, weave_height_, bumps_height_, sky_;
  gl::Buffer no_extras_{"no mesh extras"};
  gl::Buffer cloth_extras_{"cloth extras"};  // uv and tangent ends of every particle
  float scene_size_;
};

}  // namespace clothsim

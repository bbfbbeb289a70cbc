// Draws the cloth straight from the simulation's storage buffers (vertex pulling by
// gl_VertexID: no copy), and the colliders, with any of the classic shaders.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ambient_occlusion.hpp"
#include "camera.hpp"
#include "objects.hpp"
#include "program.hpp"
#include "pass_clock.hpp"
#include "reference/reference.hpp"
#include "shadow_map.hpp"
#include "texture.hpp"

namespace clothsim {

struct ColliderMesh;

enum class ShaderKind { Wireframe, Normal, Diffuse, Phong, Texture, Bump, Displacement, Mirror };
inline constexpr std::array<const char*, 8> kShaderNames{"Wireframe", "Normal", "Diffuse", "Phong",
                                                         "Texture", "Bump", "Displacement", "Mirror"};
// "Phong" -> ShaderKind::Phong (case-insensitive); nullopt for an unknown name.
std::optional<ShaderKind> parse_shader(const std::string& name);

// What the user can change about the look (the viewer's Appearance panel).
struct Appearance {
  ShaderKind shader = ShaderKind::Phong;
  glm::vec4 color{0.72f, 0.7f, 0.68f, 1.f};
  float normal_scaling = 2.f;
  float height_scaling = 0.02f;  // metres at height 1
  // Scales the light before the tone map (shaders/lighting.glsl): 2 is one stop brighter.
  float exposure = 1.f;
  bool show_spheres = true;
  bool show_planes = true;
  bool show_meshes = true;
  std::array<bool, 3> wire_springs{true, true, false};  // structural, shearing, bending
  // The look of a demo (docs/rendering.md): in the lit shaders (Diffuse, Phong, Texture, Bump,
  // Displacement) the key light casts soft shadows and ambient occlusion darkens creases and
  // contact; the studio is a background gradient, a grid floor on every plane and a sky fill light.
  bool shadows = true;
  bool ambient_occlusion = true;
  bool studio = true;
  bool floor = false;  // a studio floor under a scene that has no plane (drawn only: it does not collide)
  glm::vec3 back_tint{0.7f, 0.78f, 0.95f};  // multiplies the albedo of the cloth's back; (1, 1, 1): no tint
  // Where the key light stands: the camera's target plus this times the larger of the camera's
  // distance and the scene's size (world axes). The default is above, to the right of and in
  // front of the target; a raking light (small z, large x) shows shallow pleats (--light).
  glm::vec3 light{0.6f, 1.4f, 0.9f};

  // The classic app's look: one unshadowed light, a flat background, both sides alike.
  static Appearance classic(ShaderKind shader = ShaderKind::Phong) {
    Appearance a;
    a.shader = shader;
    a.shadows = a.ambient_occlusion = a.studio = false;
    a.back_tint = glm::vec3(1.f);
    return a;
  }
};

// Milliseconds of the last timed frame's passes (Renderer::set_timing).
struct RenderTimes {
  double shadow_ms = 0, occlusion_ms = 0, shading_ms = 0;
  bool gpu_timer = false;  // GL timestamp queries; else glFinish and the CPU clock
};

struct RendererOptions {
  int sphere_lat = 40, sphere_lon = 40;  // the classic -a / -o
  // Spheres are drawn at 0.92 r, as the classic app did, so the cloth resting on the
  // collision surface is never hidden inside the drawn sphere.
  float sphere_shrink = 0.92f;
  gl::TextureFiltering filtering{};  // of every texture
  int shadow_map_size = 2048;        // texels per side
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
  // A skinned mesh collider (or a point cache) is posed at `time` instead: its vertices, in
  // scene coordinates, uploaded again when the time changes.
  void place_colliders(const std::vector<glm::vec3>& sphere_origins, const std::vector<glm::vec3>& plane_points,
                       const std::vector<glm::vec3>& mesh_origins = {}, double time = 0);
  template <class R> void place_colliders(const Constants<R>& c) {
    std::vector<glm::vec3> spheres, planes, meshes;
    for (const auto& s : c.control.spheres) spheres.emplace_back(s.origin_radius);
    for (const auto& p : c.control.planes) planes.emplace_back(p.point);
    for (const auto& m : c.control.meshes) meshes.emplace_back(mesh_origin(m));
    place_colliders(spheres, planes, meshes, c.control.time);
  }

  // Draws into the bound framebuffer and viewport (clears it first): with the look's
  // shadows, a shadow pass from the key light; with its occlusion, a depth pre-pass and two
  // screen-space passes; then the shading pass. Every pass reads the cloth's buffers in place.
  void draw(const gl::Buffer& positions, const gl::Buffer& normals, const OrbitCamera& camera,
            const Appearance& look);

  // Times every draw's passes from now on (off: no timing, nothing waits).
  void set_timing(bool on) { timing_ = on; }
  const RenderTimes& times() const { return times_; }
  // The key light for `camera`: where `look.light` puts it from the camera's target.
  glm::vec3 light_position(const OrbitCamera& camera, const Appearance& look) const;
  // The shadow map of the last draw with shadows (null before one): for tests.
  const ShadowMap* shadow_map() const { return shadow_.get(); }
  // Where the studio floor of a scene without a plane lies (Appearance::floor): y, m.
  float floor_height() const { return floor_height_; }

  struct Mesh;  // an index buffer in a VAO, plus vertex buffers for colliders (renderer.cpp)

 private:
  enum class Pass { Casters, Depth, Shade };
  // Indices [first, first + count) of the mesh (count < 0: all of them).
  void draw_mesh(const Mesh& mesh, gl::Program& program, bool lines, GLsizei first = 0, GLsizei count = -1) const;
  // The cloth and the colliders the look shows, for one pass: casters are the cloth, spheres
  // and meshes (a plane only receives), the depth pre-pass and shading take everything.
  void draw_objects(gl::Program& prog, const gl::Buffer& positions, const gl::Buffer& normals, const Appearance& look,
                    Pass pass);
  gl::Program& program(ShaderKind kind);
  gl::Program& depth_program(bool displacement);
  void pose_meshes(double t);  // the skinned colliders' vertices at t, uploaded
  // The shown spheres' and meshes' box where they are now (lo > hi when there are none).
  std::pair<glm::vec3, glm::vec3> collider_box(const Appearance& look) const;

  const ClothModel& model_;
  std::filesystem::path root_;
  std::vector<std::optional<gl::Program>> programs_;  // built on first use
  std::array<std::optional<gl::Program>, 2> depth_programs_;  // default.vert, displacement.vert
  std::optional<gl::Program> background_;
  std::unique_ptr<ShadowMap> shadow_;
  std::unique_ptr<AmbientOcclusion> occlusion_;
  std::unique_ptr<PassClock<3>> clock_;
  gl::VertexArray empty_{"background"};
  bool timing_ = false;
  RenderTimes times_;
  std::unique_ptr<Mesh> floor_;  // Appearance::floor (scenes without a plane)
  float floor_height_ = 0;
  float floor_half_ = 0;  // half the side of every drawn plane and of the floor: 3 scene sizes
  std::vector<float> sphere_radii_;
  std::vector<std::pair<glm::vec3, glm::vec3>> mesh_boxes_;  // as built (a posed one: as last posed)
  // The skinned mesh colliders (null for a rigid one), their scene entries, and the time they
  // were last posed at (place_colliders).
  std::vector<std::shared_ptr<const ColliderMesh>> posed_;
  std::vector<MeshColliderParams> posed_params_;
  double posed_time_ = 0;
  std::unique_ptr<Mesh> cloth_;
  std::array<std::unique_ptr<Mesh>, 3> springs_;
  std::vector<std::unique_ptr<Mesh>> spheres_, planes_, meshes_;
  // Where each collider's mesh was built (the scene's origin / point) and where it is now.
  std::vector<glm::vec3> sphere_built_, plane_built_, sphere_now_, plane_now_, mesh_built_, mesh_now_;
  gl::Texture fabric_, weave_height_, bumps_height_, sky_;
  gl::Buffer no_extras_{"no mesh extras"};
  gl::Buffer cloth_extras_{"cloth extras"};  // uv and tangent ends of every particle
  float scene_size_;
  int shadow_map_size_;
};

}  // namespace clothsim

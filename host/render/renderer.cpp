#include "renderer.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "camera.hpp"
#include "context.hpp"
#include "colliders/mesh_collider.hpp"
#include "meshes.hpp"
#include "renderer_detail.hpp"
#include "scene/motion.hpp"

namespace clothsim {

// A drawable: an index buffer recorded in a VAO, and (for colliders) its own vertex buffers
// bound where the cloth's SSBOs go.
struct Renderer::Mesh {
  gl::VertexArray vao{"mesh"};
  gl::Buffer indices{"mesh indices"};
  GLsizei count = 0;
  std::optional<gl::Buffer> positions, normals, extras;  // absent for the cloth
};

namespace {

gl::Texture load_cube(const std::filesystem::path& dir, const gl::TextureFiltering& filtering) {
  std::array<std::filesystem::path, 6> faces;
  const char* names[6] = {"posx", "negx", "posy", "negy", "posz", "negz"};
  for (int f = 0; f < 6; ++f) faces[f] = dir / ("sky_" + std::string(names[f]) + ".png");
  return gl::Texture::load_cube(faces, filtering);
}

}  // namespace

std::optional<ShaderKind> parse_shader(const std::string& name) {
  auto lower = [](std::string s) {
    for (char& c : s) c = char(std::tolower((unsigned char)c));
    return s;
  };
  for (size_t k = 0; k < kShaderNames.size(); ++k)
    if (lower(kShaderNames[k]) == lower(name)) return ShaderKind(k);
  return std::nullopt;
}

namespace {
std::unique_ptr<Renderer::Mesh> make_indexed(const std::vector<uint32_t>& idx) {
  auto m = std::make_unique<Renderer::Mesh>();
  gl::upload_vector(m->indices, idx, GL_STATIC_DRAW);
  m->vao.set_element_buffer(m->indices);
  glBindVertexArray(0);
  m->count = GLsizei(idx.size());
  return m;
}

// The larger side of the cloths' bounding box at rest: how big the scene is.
float cloth_extent(const ClothModel& m) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (auto& p : m.initial) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 size = hi - lo;
  return float(std::max({size.x, size.y, size.z, 1e-6}));
}

// A drawn mesh's bounding box.
std::pair<glm::vec3, glm::vec3> box_of(const MeshData& d) {
  glm::vec3 lo(3e38f), hi(-3e38f);
  for (const glm::vec4& q : d.positions) lo = glm::min(lo, glm::vec3(q)), hi = glm::max(hi, glm::vec3(q));
  return {lo, hi};
}

// A skinned collider drawn where its animation has it at t, in scene coordinates (its origin at
// the scene's origin or keys, as collider_origin places it).
MeshData posed_mesh(const ColliderMesh& mesh, const MeshColliderParams& p, double t) {
  return surface_mesh(SurfaceMesh{posed_positions(mesh, p, keyed_at(p.motion, p.origin, t), t), mesh.surface.triangles}, glm::mat3(1.f),
                      glm::vec3(0.f));
}

std::unique_ptr<Renderer::Mesh> make_mesh(const MeshData& d) {
  auto m = make_indexed(d.indices);
  m->positions.emplace("collider positions");
  m->normals.emplace("collider normals");
  m->extras.emplace("collider extras");
  gl::upload_vector(*m->positions, d.positions, GL_STATIC_DRAW);
  gl::upload_vector(*m->normals, d.normals, GL_STATIC_DRAW);
  gl::upload_vector(*m->extras, d.extras, GL_STATIC_DRAW);
  return m;
}
}  // namespace

Renderer::Renderer(const std::filesystem::path& root, const Scene& scene, const ClothModel& model,
                   const RendererOptions& options)
    : model_(model), root_(root), programs_(kShaderNames.size()),
      fabric_(gl::Texture::load_2d(root / "textures" / "fabric.png", options.filtering)),
      weave_height_(gl::Texture::load_2d(root / "textures" / "height_weave.png", options.filtering)),
      bumps_height_(gl::Texture::load_2d(root / "textures" / "height_bumps.png", options.filtering)),
      sky_(load_cube(root / "textures", options.filtering)),
      scene_size_(cloth_extent(model)), shadow_map_size_(options.shadow_map_size) {
  floor_half_ = 3.f * scene_size_;  // big enough to look endless around the cloth
  cloth_ = make_indexed(cloth_triangle_indices(model));
  // The cloth's static per-vertex extras: uv, and in zw the particles whose difference is the
  // tangent along +u (ClothModel::tangent_ends), as floats (exact below 2^24).
  std::vector<layout::MeshVertex> extras;
  for (int i = 0; i < model.count(); ++i)
    extras.push_back({glm::vec4(float(model.uv[i].x), float(model.uv[i].y), float(model.tangent_ends[i][0]),
                                float(model.tangent_ends[i][1])),
                      glm::vec4(0.f)});
  gl::upload_vector(cloth_extras_, extras, GL_STATIC_DRAW);
  for (int t = 0; t < 3; ++t) springs_[t] = make_indexed(cloth_spring_indices(model, SpringType(t)));
  for (auto& s : scene.spheres) {
    sphere_built_.emplace_back(s.origin);
    sphere_radii_.push_back(float(s.radius));
    spheres_.push_back(make_mesh(sphere_mesh(glm::vec3(s.origin), float(s.radius) * options.sphere_shrink,
                                             options.sphere_lat, options.sphere_lon)));
  }
  glm::dvec3 centre(0);
  for (auto& p : model.initial) centre += p;
  centre /= double(model.count());
  for (auto& pl : scene.planes) {
    // A square around the cloth's shadow on the plane.
    const glm::dvec3 foot = centre - pl.normal * glm::dot(centre - pl.point, pl.normal);
    plane_built_.emplace_back(pl.point);
    planes_.push_back(make_mesh(plane_mesh(glm::vec3(foot), glm::vec3(pl.normal), floor_half_)));
  }
  for (size_t k = 0; k < scene.meshes.size(); ++k) {
    const MeshColliderParams& p = scene.meshes[k];
    mesh_built_.emplace_back(p.origin);
    const auto file = load_collider_mesh(scene, k);
    // A skinned one posed at t = 0 (posed_time_), in place; a rigid one translated by u_model.
    const MeshData drawn = file->skin ? posed_mesh(*file, p, 0.0)
                                      : surface_mesh(file->surface, glm::mat3(collider_rotation(p)), glm::vec3(p.origin));
    mesh_boxes_.push_back(box_of(drawn));
    meshes_.push_back(make_mesh(drawn));
    posed_.push_back(file->skin ? file : nullptr);
    posed_params_.push_back(p);
  }
  // The studio floor of a scene without a plane: just below the lowest of where the cloth
  // starts, where it will roughly rest and the colliders, so a hanging cloth hangs above it.
  double lowest = 1e300;
  for (auto& q : model.initial) lowest = std::min(lowest, q.y);
  for (auto& q : resting_points(scene, model)) lowest = std::min(lowest, q.y);
  for (auto& sp : scene.spheres) lowest = std::min(lowest, sp.origin.y - sp.radius);
  for (auto& box : mesh_boxes_) lowest = std::min(lowest, double(box.first.y));
  floor_height_ = float(lowest) - 0.02f * scene_size_;
  if (scene.planes.empty())
    floor_ = make_mesh(plane_mesh(glm::vec3(float(centre.x), floor_height_, float(centre.z)), glm::vec3(0, 1, 0), floor_half_));
  no_extras_.allocate(sizeof(layout::MeshVertex));
  sphere_now_ = sphere_built_;
  plane_now_ = plane_built_;
  mesh_now_ = mesh_built_;
}

// A skinned collider's vertices where its animation has them at t (and its origin, at the
// scene's origin or keys), drawn in place: mesh_now_ stays mesh_built_, so nothing translates them again.
void Renderer::pose_meshes(double t) {
  posed_time_ = t;
  for (size_t k = 0; k < posed_.size(); ++k) {
    if (!posed_[k]) continue;
    const MeshData drawn = posed_mesh(*posed_[k], posed_params_[k], t);
    meshes_[k]->positions->upload(0, drawn.positions.size() * sizeof(glm::vec4), drawn.positions.data());
    meshes_[k]->normals->upload(0, drawn.normals.size() * sizeof(glm::vec4), drawn.normals.data());
    mesh_boxes_[k] = box_of(drawn);
  }
}

void Renderer::place_colliders(const std::vector<glm::vec3>& sphere_origins, const std::vector<glm::vec3>& plane_points,
                               const std::vector<glm::vec3>& mesh_origins, double time) {
  if (sphere_origins.size() != sphere_built_.size() || plane_points.size() != plane_built_.size() ||
      (!mesh_origins.empty() && mesh_origins.size() != mesh_built_.size()))
    throw std::logic_error("Renderer::place_colliders: not the scene's number of spheres, planes and meshes");
  sphere_now_ = sphere_origins;
  plane_now_ = plane_points;
  if (!mesh_origins.empty()) mesh_now_ = mesh_origins;
  for (size_t k = 0; k < posed_.size(); ++k)
    if (posed_[k]) mesh_now_[k] = mesh_built_[k];  // posed in place
  if (time != posed_time_) pose_meshes(time);
}

Renderer::~Renderer() = default;

gl::Program& Renderer::program(ShaderKind kind) {
  auto& slot = programs_[size_t(kind)];
  if (!slot) {
    std::string name = kShaderNames[size_t(kind)];
    for (char& c : name) c = char(std::tolower((unsigned char)c));
    const auto dir = root_ / "shaders";
    const auto vert = kind == ShaderKind::Displacement ? dir / "displacement.vert" : dir / "default.vert";
    slot = gl::Program::graphics(vert, dir / (name + ".frag"), {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}});
  }
  return *slot;
}

void Renderer::draw_mesh(const Mesh& mesh, gl::Program& prog, bool lines, GLsizei first, GLsizei count) const {
  prog.use();
  mesh.vao.bind();
  glDrawElements(lines ? GL_LINES : GL_TRIANGLES, count < 0 ? mesh.count : count, GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(uintptr_t(first) * sizeof(uint32_t)));
  glBindVertexArray(0);
}

glm::vec3 Renderer::light_position(const OrbitCamera& camera, const Appearance& look) const {
  return camera.target + look.light * std::max(camera.distance, scene_size_);
}

std::pair<glm::vec3, glm::vec3> Renderer::collider_box(const Appearance& look) const {
  glm::vec3 lo(3e38f), hi(-3e38f);
  for (size_t k = 0; k < sphere_now_.size() && look.show_spheres; ++k) {
    lo = glm::min(lo, sphere_now_[k] - glm::vec3(sphere_radii_[k]));
    hi = glm::max(hi, sphere_now_[k] + glm::vec3(sphere_radii_[k]));
  }
  for (size_t k = 0; k < mesh_boxes_.size() && look.show_meshes; ++k) {
    const glm::vec3 moved = mesh_now_[k] - mesh_built_[k];
    lo = glm::min(lo, mesh_boxes_[k].first + moved);
    hi = glm::max(hi, mesh_boxes_[k].second + moved);
  }
  return {lo, hi};
}

gl::Program& Renderer::depth_program(bool displacement) {
  auto& slot = depth_programs_[displacement ? 1 : 0];
  if (!slot) {
    const auto dir = root_ / "shaders";
    slot = gl::Program::graphics(dir / (displacement ? "displacement.vert" : "default.vert"), dir / "depth.frag",
                                 {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}});
  }
  return *slot;
}

void Renderer::draw_objects(gl::Program& prog, const gl::Buffer& positions, const gl::Buffer& normals,
                            const Appearance& look, Pass pass) {
  const bool shade = pass == Pass::Shade;
  const bool wire = shade && look.shader == ShaderKind::Wireframe;
  const bool studio_floor = shade && look.studio && is_lit(look.shader);
  auto colour = [&](glm::vec4 c) {
    if (shade) prog.set("u_color", c);
  };
  // The cloth: the simulation's own buffers, read in place by the vertex shader.
  prog.set("u_model", glm::mat4(1.f));
  positions.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_POSITIONS);
  normals.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_NORMALS);
  cloth_extras_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_EXTRAS);
  prog.set("u_is_cloth", 1);
  if (shade) prog.set("u_is_floor", 0);
  if (wire) {
    colour(glm::vec4(0.95f, 0.95f, 0.95f, 1.f));
    for (int t = 0; t < 3; ++t)
      if (look.wire_springs[t]) draw_mesh(*springs_[t], prog, true);
  } else {
    // Each cloth of the scene in its own colour (the first in the appearance's), so two cloths
    // lying on each other can be told apart.
    static const glm::vec4 kOthers[] = {{0.85f, 0.42f, 0.30f, 1.f}, {0.35f, 0.62f, 0.45f, 1.f}, {0.55f, 0.45f, 0.75f, 1.f}};
    for (size_t k = 0; k < model_.parts.size(); ++k) {
      const ClothPart& part = model_.parts[k];
      colour(k == 0 ? look.color : kOthers[(k - 1) % 3]);
      draw_mesh(*cloth_, prog, false, GLsizei(3 * part.first_triangle), GLsizei(3 * part.triangle_count));
    }
  }

  // Colliders: their own buffers at the same bindings, shaded with the same program.
  prog.set("u_is_cloth", 0);
  auto draw_collider = [&](const Mesh& m, glm::vec3 moved, glm::vec4 c) {
    // Only a translation, so the normals (mat3(u_model)) are unchanged.
    prog.set("u_model", glm::translate(glm::mat4(1.f), moved));
    m.positions->bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_POSITIONS);
    m.normals->bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_NORMALS);
    m.extras->bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DRAW_EXTRAS);
    colour(c);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    draw_mesh(m, prog, false);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  };
  if (look.show_spheres)
    for (size_t k = 0; k < spheres_.size(); ++k)
      draw_collider(*spheres_[k], sphere_now_[k] - sphere_built_[k], wire ? glm::vec4(0.45f, 0.6f, 0.9f, 1.f) : glm::vec4(0.35f, 0.5f, 0.8f, 1.f));
  if (look.show_meshes)
    for (size_t k = 0; k < meshes_.size(); ++k)
      draw_collider(*meshes_[k], mesh_now_[k] - mesh_built_[k], wire ? glm::vec4(0.8f, 0.6f, 0.4f, 1.f) : glm::vec4(0.62f, 0.52f, 0.42f, 1.f));
  if (pass == Pass::Casters) return;  // a plane only receives: a floor shadowing the scene it holds up would hide it
  const bool floor_drawn = look.floor && floor_;
  if (look.show_planes || floor_drawn) {
    // Cloth resting on a plane lies 0.1 mm above it (the contact's offset), which the depth
    // buffer cannot tell apart at a few metres: push the plane's depth back a little so the
    // cloth wins instead of both speckling through each other.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.f, 4.f);
    if (studio_floor) {
      prog.set("u_is_floor", 1);
      prog.set("u_floor_half", floor_half_);
      // Fine lines a power of ten apart, some 10 to 100 across the cloth: 10 cm under a 1 m cloth.
      prog.set("u_grid", std::pow(10.f, std::floor(std::log10(scene_size_)) - 1.f));
    }
    const glm::vec4 floor_colour = wire ? glm::vec4(0.4f, 0.4f, 0.4f, 1.f) : glm::vec4(0.3f, 0.31f, 0.33f, 1.f);
    if (look.show_planes)
      for (size_t k = 0; k < planes_.size(); ++k) draw_collider(*planes_[k], plane_now_[k] - plane_built_[k], floor_colour);
    if (floor_drawn) draw_collider(*floor_, glm::vec3(0.f), floor_colour);
    if (shade) prog.set("u_is_floor", 0);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
}


}  // namespace clothsim

// --export-colliders (collider_export.hpp). A rigid mesh collider moves by translation only
// (its `motion` keys its origin; docs/model.md, "Mesh colliders"): at time t its vertices are
// R v + origin(t), R its fixed rotation, v the file's vertex scaled, as the simulation places
// it for the substep ending at t (set_substep_time evaluates the same keys); a skinned one is
// posed by its animation at t too (posed_positions). At the end of a run the frames are also
// written as one point cache a collider, DIR/meshK/mesh.pc2.
#include "export/collider_export.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "export/output_plan.hpp"
#include "io/output_file.hpp"
#include "io/point_cache.hpp"
#include "scene/motion.hpp"

namespace clothsim {
namespace {

namespace fs = std::filesystem;

std::string frame_name(int64_t frame) { return fmt::format("frame_{:04d}.obj", frame); }

// Every exported frame of one collider as a point cache over the first frame's OBJ (the same
// vertices in the same order at every frame), which Blender's Mesh Cache modifier plays.
constexpr const char* kColliderCache = "mesh.pc2";

void write_collider_obj(const std::string& path, const ColliderMesh& mesh, const std::vector<glm::dvec3>& posed,
                        const std::string& key, double time) {
  write_text_file(path, [&](std::FILE* f) {  // replaced only once complete (io/output_file.hpp)
    fmt::print(f, "# clothsim collider {} at t = {:.9g} s, {} triangles, scene coordinates\n", key, time,
               mesh.surface.triangles.size());
    for (const glm::dvec3& p : posed) fmt::print(f, "v {:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
    for (const glm::uvec3& t : mesh.surface.triangles) fmt::print(f, "f {} {} {}\n", t.x + 1, t.y + 1, t.z + 1);
  });
}

}  // namespace

std::string collider_folder(const std::string& dir, size_t k) {
  return (fs::path(strip_slashes(dir)) / fmt::format("mesh{}", k)).string();
}

void plan_collider_export(OutputPlan& plan, const Scene& scene, const std::string& dir, int64_t start, int frames,
                          int every) {
  std::vector<std::string> names;
  for (int64_t f = start; f <= start + frames; f += every) names.push_back(frame_name(f));
  names.push_back(kColliderCache);
  for (size_t k = 0; k < scene.meshes.size(); ++k) plan.folder("--export-colliders", collider_folder(dir, k), names);
}

ColliderExport::ColliderExport(const Scene& scene, const std::string& dir, int64_t start, int every)
    : scene_(scene), dir_(strip_slashes(dir)), start_(start), every_(every) {
  for (size_t k = 0; k < scene.meshes.size(); ++k) {
    meshes_.push_back(load_collider_mesh(scene, k));
    const std::string folder = collider_folder(dir, k);
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder))
      throw std::runtime_error(fmt::format("{}: cannot create the directory ({})", folder, ec.message()));
    caches_.push_back(std::make_unique<PendingFile>((fs::path(folder) / kColliderCache).string()));
    writers_.push_back(std::make_unique<Pc2Writer>(caches_.back()->temp(), int(meshes_.back()->surface.positions.size()),
                                                   float(start), float(every)));
  }
}

void ColliderExport::add(int64_t frame, double time) {
  for (size_t k = 0; k < meshes_.size(); ++k) {
    const std::vector<glm::dvec3> posed =
        posed_positions(*meshes_[k], scene_.meshes[k], collider_origin(scene_, ColliderRef{3, k}, time), time);
    write_collider_obj((fs::path(collider_folder(dir_, k)) / frame_name(frame)).string(), *meshes_[k], posed,
                       mesh_key(scene_, k), time);
    std::vector<glm::dvec4> sample;
    for (const glm::dvec3& p : posed) sample.push_back(glm::dvec4(p, 0.0));
    writers_[k]->add(sample);
  }
  if (written_++ == 0) first_ = frame;
  last_ = frame;
}

void ColliderExport::finish() {
  for (size_t k = 0; k < meshes_.size() && written_ > 0; ++k) {
    writers_[k]->close();
    caches_[k]->commit();
  }
  cached_ = written_ > 0;
}

std::string ColliderExport::summary() const {
  return fmt::format("{} collider{} x {} frame{} ({}/mesh*/frame_{:04d}.obj ... frame_{:04d}.obj{})", meshes_.size(),
                     meshes_.size() == 1 ? "" : "s", written_, written_ == 1 ? "" : "s", dir_, first_, last_,
                     cached_ ? fmt::format(", and each as {}", kColliderCache) : "");
}

}  // namespace clothsim

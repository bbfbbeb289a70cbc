// Mesh colliders: file -> triangles in metres -> signed distance field, memoised per process,
// the field cached on disk when it took over a second to build.
#include "colliders/mesh_collider.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <tuple>

#include <fmt/format.h>

#include "cloth/mesh_import.hpp"
#include "io/input_file.hpp"

namespace clothsim {
namespace {

struct Key {
  std::string file;
  double scale, voxel_size;
  std::string animation;
  double time_scale;
  bool loop;
  std::string point_cache, sequence;
  double cache_rate;
  auto operator<=>(const Key&) const = default;
};

std::mutex g_mutex;
std::map<Key, std::shared_ptr<const ColliderMesh>> g_loaded;

SurfaceMesh surface_of(const PolyMesh& poly, double scale) {
  SurfaceMesh m;
  m.positions.reserve(poly.positions.size());
  for (const glm::dvec3& p : poly.positions) m.positions.push_back(p * scale);
  for (const auto& f : poly.faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    if (f.size() == 4) m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

double longest_extent(const SurfaceMesh& m) {
  glm::dvec3 lo(m.positions[m.triangles[0][0]]), hi = lo;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) lo = glm::min(lo, m.positions[t[k]]), hi = glm::max(hi, m.positions[t[k]]);
  return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

bool g_cache_enabled = true;

// Where a field that took long to build is kept: the cache folder, named by the mesh's stem and
// hash and the spacing's bits; none with --no-cache or without a cache folder.
std::filesystem::path cache_path(const std::filesystem::path& mesh, uint64_t hash, double voxel) {
  const std::filesystem::path dir = field_cache_folder();
  if (dir.empty()) return {};
  uint64_t bits;
  std::memcpy(&bits, &voxel, sizeof bits);
  return dir / fmt::format("{}-{:016x}-{:016x}.sdf", mesh.stem().string(), hash, bits);
}

}  // namespace

void disable_field_cache() { g_cache_enabled = false; }

std::filesystem::path field_cache_folder() {
  if (!g_cache_enabled) return {};
  // The XDG base directory rule: $XDG_CACHE_HOME if set to an absolute path, else ~/.cache.
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && xdg[0] == '/') return std::filesystem::path(xdg) / "clothsim";
  if (const char* home = std::getenv("HOME"); home && home[0] == '/')
    return std::filesystem::path(home) / ".cache" / "clothsim";
  return {};
}

std::string mesh_key(const Scene& scene, size_t index) {
  return scene.meshes.size() == 1 ? std::string("mesh") : fmt::format("mesh[{}]", index);
}

glm::dmat3 collider_rotation(const MeshColliderParams& p) {
  const double a = p.rotation_degrees * (3.14159265358979323846 / 180.0);
  const double c = std::cos(a), s = std::sin(a), t = 1 - c;
  const glm::dvec3 k = p.rotation_axis;
  // Rodrigues: R = c I + s [k]x + t k k^T, column by column (glm is column-major).
  return glm::dmat3(glm::dvec3(c + t * k.x * k.x, t * k.x * k.y + s * k.z, t * k.x * k.z - s * k.y),
                    glm::dvec3(t * k.x * k.y - s * k.z, c + t * k.y * k.y, t * k.y * k.z + s * k.x),
                    glm::dvec3(t * k.x * k.z + s * k.y, t * k.y * k.z - s * k.x, c + t * k.z * k.z));
}

std::vector<glm::dvec3> posed_positions(const ColliderMesh& mesh, const MeshColliderParams& p, const glm::dvec3& origin,
                                        double t) {
  const glm::dmat3 rotation = collider_rotation(p);
  std::vector<glm::dvec3> out;
  out.reserve(mesh.surface.positions.size());
  const std::vector<glm::dmat4> bones = mesh.skin ? mesh.skin->palette_at(t) : std::vector<glm::dmat4>{};
  for (size_t v = 0; v < mesh.surface.positions.size(); ++v) {
    glm::dvec3 q = mesh.surface.positions[v];
    if (mesh.skin) {  // B on the scaled vertex: its linear part as it is, its translation scaled
      glm::dvec3 sum(0.0);
      for (int k = 0; k < kBonesPerVertex; ++k) {
        const glm::dmat4& b = bones[mesh.skin->bones[v][k]];
        sum += mesh.skin->weights[v][k] * (glm::dmat3(b) * q + p.scale * glm::dvec3(b[3]));
      }
      q = sum;
    }
    out.push_back(rotation * q + origin);
  }
  return out;
}

std::shared_ptr<const ColliderMesh> load_collider_mesh(const Scene& scene, size_t index) {
  const MeshColliderParams& p = scene.meshes.at(index);
  const std::string key = mesh_key(scene, index);
  std::lock_guard lock(g_mutex);
  const double rate = p.cache_frames_per_sec > 0 ? p.cache_frames_per_sec : scene.simulation.frames_per_sec;
  const Key memo{p.file_path.string(), p.scale, p.voxel_size, p.animation, p.time_scale, p.loop,
                 p.point_cache_path.string(), p.sequence_path.string(), rate};
  if (auto it = g_loaded.find(memo); it != g_loaded.end()) return it->second;

  auto out = std::make_shared<ColliderMesh>();
  out->file = p.file_path;
  auto keep = [&](Skin skin) {  // what moves the vertices, played as the scene says
    skin.time_scale = p.time_scale;
    skin.loop = p.loop;
    out->skin = std::make_shared<Skin>(std::move(skin));
  };
  MeshInspector read_bones;
  if (!p.animation.empty())
    read_bones = [&](const aiScene& file, std::span<const MeshUse> uses, size_t vertices) {
      keep(read_skin(file, uses, vertices, p.animation,
                     fmt::format("{}: {}.animation: {}", scene.source, key, printable(p.file_path.string()))));
    };
  const PolyMesh poly = load_mesh(p.file_path, fmt::format("{}: {}.file", scene.source, key), /*manifold=*/false, read_bones);
  out->surface = surface_of(poly, p.scale);
  if (!p.point_cache.empty() || !p.sequence.empty()) {
    const bool pc2 = !p.point_cache.empty();
    const std::string what = fmt::format("{}: {}.{}", scene.source, key, pc2 ? "point_cache" : "sequence");
    keep(pc2 ? read_point_cache(poly.positions, p.point_cache_path, rate, what)
             : read_obj_sequence(poly.positions, p.sequence_path, rate, what));
  }
  const double extent = longest_extent(out->surface);
  if (!(extent > 0))
    throw SceneError(fmt::format("{}: {}.file: {}: the mesh is a point (no extent to collide with)", scene.source, key,
                                 p.file_path.string()));
  const double voxel = p.voxel_size > 0 ? p.voxel_size : extent / kDefaultSdfDivisions;
  const double bytes = sdf_nodes(out->surface, voxel) * sizeof(float);
  if (bytes > double(kMaxSdfBytes)) {
    // The node count goes as 1 / voxel^3 (the padding aside): the spacing that fits, found by
    // growing that estimate until it does.
    double fits = voxel * std::cbrt(bytes / double(kMaxSdfBytes));
    while (sdf_nodes(out->surface, fits) * sizeof(float) > double(kMaxSdfBytes)) fits *= 1.01;
    throw SceneError(fmt::format("{}: {}.voxel_size: a spacing of {:.4g} m needs {:.0f} MiB for the field of {} "
                                 "(at most {} MiB); expected a voxel_size of at least {:.3g} m",
                                 scene.source, key, voxel, bytes / double(1 << 20), p.file_path.string(),
                                 kMaxSdfBytes >> 20, fits));
  }
  const uint64_t hash = mesh_hash(out->surface);
  const std::filesystem::path cache = cache_path(p.file_path, hash, voxel);
  std::string problem;
  if (!cache.empty() && read_sdf_cache(cache, hash, voxel, out->sdf, &problem)) {
    out->from_cache = true;
    out->cache = cache;
  } else {
    if (!problem.empty())
      fmt::print(stderr, "note: {}: {}: the cached field {} failed its check ({}); building it again\n", scene.source,
                 key, cache.string(), problem);
    const auto t0 = std::chrono::steady_clock::now();
    out->sdf = build_sdf(out->surface, voxel);
    out->build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!cache.empty() && out->build_seconds > kSdfCacheSeconds) {
      try {
        std::filesystem::create_directories(cache.parent_path());
        write_sdf_cache(cache, hash, out->sdf);
        out->cache = cache;
      } catch (const std::exception& e) {  // a read-only folder: the run goes on without a cache
        fmt::print(stderr, "warning: {}: {}: could not keep the field in {} ({})\n", scene.source, key,
                   cache.string(), e.what());
      }
    }
  }
  if (!out->sdf.closed)
    fmt::print(stderr,
               "note: {}: {}.file: {} has {} boundary edges (an open surface): its inside is where its winding "
               "number is above 1/2, which closes its holes; where it is a thin sheet it collides as a shell of "
               "thickness {} m (docs/model.md, \"Mesh colliders\")\n",
               scene.source, key, p.file_path.string(), out->sdf.boundary_edges, p.thickness);
  g_loaded.emplace(memo, out);
  return out;
}

std::shared_ptr<const std::vector<float>> concatenated_fields(const std::vector<std::shared_ptr<const ColliderMesh>>& meshes) {
  if (meshes.size() == 1) return {meshes[0], &meshes[0]->sdf.values};  // shares the mesh's own array
  static std::map<std::vector<const ColliderMesh*>, std::shared_ptr<const std::vector<float>>> joined;
  std::vector<const ColliderMesh*> key;
  for (const auto& m : meshes) key.push_back(m.get());
  std::lock_guard lock(g_mutex);
  auto& slot = joined[key];
  if (!slot) {
    auto all = std::make_shared<std::vector<float>>();
    for (const auto& m : meshes) all->insert(all->end(), m->sdf.values.begin(), m->sdf.values.end());
    slot = all;
  }
  return slot;
}

std::vector<std::string> collider_mesh_report() {
  std::lock_guard lock(g_mutex);
  std::vector<std::string> lines;
  for (const auto& [key, m] : g_loaded) {
    const SdfGrid& g = m->sdf;
    std::string how = m->from_cache ? fmt::format("read from {}", m->cache.string())
                                    : fmt::format("built in {:.2f} s{}", m->build_seconds,
                                                  m->cache.empty() ? "" : ", kept in " + m->cache.string());
    lines.push_back(fmt::format("{}: {} triangles, {} field {}x{}x{} nodes of {:.2f} mm ({:.1f} MiB), {}",
                                m->file.string(), m->surface.triangles.size(), g.closed ? "signed" : "winding-signed (open)",
                                g.dims.x, g.dims.y, g.dims.z, g.voxel * 1000, double(g.bytes()) / (1 << 20), how));
  }
  return lines;
}

}  // namespace clothsim

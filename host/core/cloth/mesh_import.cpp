// load_mesh: Assimp reads the file; this file puts the particles back in the file's order
// (mesh_import.hpp says which order per format and why), welds, checks and cleans the faces.
#include "cloth/mesh_import.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "io/input_file.hpp"
#include "io/gltf_check.hpp"
#include "io/ply_check.hpp"
#include "scene/scene.hpp"
#include "cloth/mesh_import_detail.hpp"

namespace clothsim {
namespace {

namespace fs = std::filesystem;
using mesh_import_detail::Context;
using mesh_import_detail::read_obj_positions;


// One use of an aiMesh by a node, with the node's transform accumulated from the root.
struct Instance {
  const aiMesh* mesh;
  glm::dmat4 transform;
  const aiNode* node;
};

// Depth first, a node's meshes before its children, children in order. An explicit stack:
// a hostile file's node tree can be deeper than the call stack.
std::vector<Instance> collect_instances(const aiScene& scene) {
  std::vector<Instance> out;
  std::vector<std::pair<const aiNode*, glm::dmat4>> stack;
  if (scene.mRootNode) stack.emplace_back(scene.mRootNode, glm::dmat4(1.0));
  while (!stack.empty()) {
    auto [node, parent] = stack.back();
    stack.pop_back();
    glm::dmat4 local;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) local[c][r] = node->mTransformation[r][c];  // row major to glm's columns
    const glm::dmat4 world = parent * local;
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
      if (node->mMeshes[i] < scene.mNumMeshes) out.push_back({scene.mMeshes[node->mMeshes[i]], world, node});
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], world);
  }
  return out;
}

// Exact-position keys for welding: the bit patterns, with -0 made +0 (they are equal).
template <class T, class Bits>
struct PositionKey {
  Bits b[3];
  bool operator==(const PositionKey&) const = default;
  static PositionKey of(T x, T y, T z) { return {{std::bit_cast<Bits>(T(x + T(0))), std::bit_cast<Bits>(T(y + T(0))), std::bit_cast<Bits>(T(z + T(0)))}}; }
};
template <class Key>
struct KeyHash {
  size_t operator()(const Key& k) const {
    uint64_t h = 1469598103934665603ull;
    for (auto w : k.b) h = (h ^ uint64_t(w)) * 1099511628211ull, h ^= h >> 29;
    return size_t(h);
  }
};
using FloatKey = PositionKey<float, uint32_t>;
using DoubleKey = PositionKey<double, uint64_t>;

bool is_obj(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".obj";
}

// Maps every Assimp vertex of an OBJ to its `v` line (see the header for why). Returns
// nothing when some vertex matches no line within 2 ulps per coordinate.
std::optional<std::vector<std::vector<uint32_t>>> match_obj_vertices(const std::vector<Instance>& instances,
                                                                     const std::vector<glm::dvec3>& file) {
  std::unordered_map<FloatKey, uint32_t, KeyHash<FloatKey>> index;
  index.reserve(file.size());
  for (size_t i = 0; i < file.size(); ++i)
    index.try_emplace(FloatKey::of(float(file[i].x), float(file[i].y), float(file[i].z)), uint32_t(i));  // the first line wins

  std::vector<std::vector<uint32_t>> map(instances.size());
  for (size_t m = 0; m < instances.size(); ++m) {
    const aiMesh& mesh = *instances[m].mesh;
    map[m].resize(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& a = mesh.mVertices[v];
      if (auto it = index.find(FloatKey::of(a.x, a.y, a.z)); it != index.end()) {
        map[m][v] = it->second;
        continue;
      }
      // Neighbours up to 2 ulps away on each axis, nearest (in ulps, then lowest index) first.
      float near[3][5];
      for (int k = 0; k < 3; ++k) {
        const float c = (&a.x)[k];
        near[k][2] = c;
        near[k][1] = std::nextafter(c, -INFINITY), near[k][0] = std::nextafter(near[k][1], -INFINITY);
        near[k][3] = std::nextafter(c, INFINITY), near[k][4] = std::nextafter(near[k][3], INFINITY);
      }
      int best_distance = 1 << 30;
      uint32_t best = 0;
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
          for (int k = 0; k < 5; ++k) {
            auto it = index.find(FloatKey::of(near[0][i], near[1][j], near[2][k]));
            if (it == index.end()) continue;
            const int distance = std::abs(i - 2) + std::abs(j - 2) + std::abs(k - 2);
            if (distance < best_distance || (distance == best_distance && it->second < best))
              best_distance = distance, best = it->second;
          }
      if (best_distance == 1 << 30) return std::nullopt;
      map[m][v] = best;
    }
  }
  return map;
}

// Every other format (or an OBJ whose order could not be recovered): Assimp's order, welded
// by exact transformed position.
std::vector<std::vector<uint32_t>> weld_vertices(const Context& cx, const std::vector<Instance>& instances,
                                                 std::vector<glm::dvec3>& positions) {
  std::unordered_map<DoubleKey, uint32_t, KeyHash<DoubleKey>> index;
  std::vector<std::vector<uint32_t>> map(instances.size());
  for (size_t m = 0; m < instances.size(); ++m) {
    const aiMesh& mesh = *instances[m].mesh;
    map[m].resize(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& a = mesh.mVertices[v];
      const glm::dvec3 p(instances[m].transform * glm::dvec4(a.x, a.y, a.z, 1.0));
      auto [it, added] = index.try_emplace(DoubleKey::of(p.x, p.y, p.z), uint32_t(positions.size()));
      if (added) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          cx.fail(fmt::format("vertex {} has a non-finite coordinate ({}, {}, {})", positions.size(), p.x, p.y, p.z));
        if (positions.size() == kMaxMeshVertices)
          cx.fail(fmt::format("more than {} vertices (the largest cloth accepted)", kMaxMeshVertices));
        positions.push_back(p);
      }
      map[m][v] = it->second;
    }
  }
  return map;
}

// Zero area relative to the face's size: twice the area at most 1e-12 of its longest edge
// (or diagonal) squared. A quad is degenerate when both halves are (all corners collinear).
bool zero_area(const std::vector<glm::dvec3>& p, const uint32_t* c, size_t n) {
  double longest2 = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const glm::dvec3 d = p[c[j]] - p[c[i]];
      longest2 = std::max(longest2, glm::dot(d, d));
    }
  auto flat = [&](uint32_t a, uint32_t b, uint32_t d) {
    const glm::dvec3 x = glm::cross(p[b] - p[a], p[d] - p[a]);
    const double limit = 1e-12 * longest2;
    return glm::dot(x, x) <= limit * limit;
  };
  return n == 3 ? flat(c[0], c[1], c[2]) : flat(c[0], c[1], c[2]) && flat(c[0], c[2], c[3]);
}

}  // namespace

PolyMesh load_mesh(const std::filesystem::path& file, const std::string& what, bool manifold, const MeshInspector& inspect) {
  const Context cx{file, what};
  // stat first: Assimp would block on a FIFO or read /dev/zero without end.
  uint64_t size = 0;
  if (auto problem = input_file_problem(file, &size)) {
    if (*problem == "does not exist") cx.fail("the mesh file does not exist");
    cx.fail(fmt::format("the mesh file {}", *problem));
  }
  if (!std::ifstream(file, std::ios::binary)) cx.fail("cannot open the mesh file (is it readable?)");
  // Assimp trusts a PLY header's counts and allocates from them: they are checked against the
  // file's size first (ply_check.hpp), and an ASCII PLY's data lines against them.
  if (auto problem = ply_problem(file, size)) cx.fail(*problem);
  if (auto problem = gltf_problem(file, size)) cx.fail(*problem);

  // No post-processing: not aiProcess_Triangulate (quads stay quads), not JoinIdenticalVertices
  // (it keeps a uv seam apart; welding here is by position alone), not ValidateDataStructure
  // (it calls a point cloud or an empty OBJ "invalid" where "no faces" is the useful message;
  // the indices and arrays used here are checked below instead).
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(file.string(), 0);
  } catch (const std::exception& e) {
    cx.fail(fmt::format("Assimp cannot read it: {}", e.what()));
  }
  if (!scene) cx.fail(fmt::format("Assimp cannot read it: {}", importer.GetErrorString()));

  const std::vector<Instance> instances = collect_instances(*scene);
  size_t polygons = 0;
  bool all_uv = true;
  for (const Instance& inst : instances) {
    const aiMesh& mesh = *inst.mesh;
    if ((mesh.mNumVertices > 0 && !mesh.mVertices) || (mesh.mNumFaces > 0 && !mesh.mFaces))
      cx.fail("Assimp returned a mesh without its vertices or faces");
    size_t here = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      if (mesh.mFaces[f].mNumIndices > 0 && !mesh.mFaces[f].mIndices) cx.fail("Assimp returned a face without its indices");
      here += mesh.mFaces[f].mNumIndices >= 3;
    }
    polygons += here;
    if (here > 0 && !inst.mesh->HasTextureCoords(0)) all_uv = false;
  }
  if (polygons == 0) cx.fail("the mesh has no faces (only points or lines, or nothing)");

  PolyMesh out;
  std::vector<std::vector<uint32_t>> particle;  // [instance][Assimp vertex] -> particle
  bool weld = true;
  if (is_obj(file)) {
    out.positions = read_obj_positions(cx);
    if (auto map = match_obj_vertices(instances, out.positions)) {
      particle = std::move(*map);
      weld = false;
    } else {
      cx.warn("cannot match Assimp's vertices to the file's `v` lines; the particles are in order of first use by the faces");
      out.positions.clear();
    }
  }
  if (weld) particle = weld_vertices(cx, instances, out.positions);
  if (inspect) {
    std::vector<MeshUse> uses;
    for (size_t m = 0; m < instances.size(); ++m)
      uses.push_back({instances[m].mesh, instances[m].node, instances[m].transform, particle[m]});
    inspect(*scene, uses, out.positions.size());
  }

  if (all_uv) {  // the first uv met per particle
    out.uv.assign(out.positions.size(), glm::dvec2(0.0));
    std::vector<bool> seen(out.positions.size(), false);
    for (size_t m = 0; m < instances.size(); ++m) {
      const aiMesh& mesh = *instances[m].mesh;
      if (!mesh.HasTextureCoords(0)) continue;
      for (unsigned v = 0; v < mesh.mNumVertices; ++v)
        if (const uint32_t i = particle[m][v]; !seen[i])
          seen[i] = true, out.uv[i] = {mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y};
    }
  }

  size_t degenerate = 0, points_lines = 0;
  std::vector<uint32_t> c;
  out.faces.reserve(polygons);
  for (size_t m = 0; m < instances.size(); ++m) {
    const aiMesh& mesh = *instances[m].mesh;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3) {
        ++points_lines;
        continue;
      }
      c.resize(face.mNumIndices);
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) cx.fail("a face refers to a vertex that does not exist");
        c[k] = particle[m][face.mIndices[k]];
      }
      std::vector<uint32_t> sorted = c;
      std::sort(sorted.begin(), sorted.end());
      if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
        ++degenerate;
        continue;
      }
      if (c.size() <= 4) {
        if (zero_area(out.positions, c.data(), c.size())) ++degenerate;
        else out.faces.push_back(c);
        continue;
      }
      for (size_t k = 1; k + 1 < c.size(); ++k) {  // a fan from the first corner
        const uint32_t tri[3] = {c[0], c[k], c[k + 1]};
        if (zero_area(out.positions, tri, 3)) ++degenerate;
        else out.faces.push_back({tri[0], tri[1], tri[2]});
      }
    }
  }
  if (points_lines > 0) cx.warn(fmt::format("ignored {} points and lines (a cloth is made of its faces)", points_lines));
  if (degenerate > 0)
    cx.warn(fmt::format("dropped {} degenerate face{} (zero area or a repeated vertex)", degenerate, degenerate == 1 ? "" : "s"));
  if (out.faces.empty()) cx.fail(fmt::format("the mesh has no faces left after dropping {} degenerate ones", degenerate));

  // A cloth surface is a 2-manifold (with boundary): an edge in three faces has no cloth meaning
  // (and would give its bending springs no opposite pair).
  if (!manifold) return out;
  std::unordered_map<uint64_t, uint8_t> uses;
  uses.reserve(out.faces.size() * 2);
  for (const auto& face : out.faces)
    for (size_t k = 0; k < face.size(); ++k) {
      const uint32_t a = face[k], b = face[(k + 1) % face.size()];
      if (++uses[(uint64_t(std::min(a, b)) << 32) | std::max(a, b)] > 2)
        cx.fail(fmt::format("the edge between vertices {} and {} (0-based) is shared by more than two faces (non-manifold)",
                            std::min(a, b), std::max(a, b)));
    }
  return out;
}

}  // namespace clothsim

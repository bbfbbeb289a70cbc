// Signed distance fields of triangle meshes (sdf.hpp): exact in a narrow band, signed by
// pseudo-normals, the far field's sign by a flood fill.
#include "colliders/sdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "colliders/winding.hpp"
#include "io/output_file.hpp"

namespace clothsim {
namespace {

using glm::dvec3;

struct Bounds {
  dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
};

Bounds bounds_of(const SurfaceMesh& mesh) {
  Bounds b;
  for (const glm::uvec3& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      b.lo = glm::min(b.lo, mesh.positions[t[k]]);
      b.hi = glm::max(b.hi, mesh.positions[t[k]]);
    }
  return b;
}

// The grid around the mesh: padded by the band and one node, so that every border node is
// further than the band from the surface (outside, where the flood fill starts).
void place_grid(const SurfaceMesh& mesh, double voxel, SdfGrid& g) {
  const Bounds b = bounds_of(mesh);
  g.voxel = voxel;
  g.band = kSdfBandVoxels * voxel;
  const double pad = g.band + voxel;
  g.min = b.lo - dvec3(pad);
  const dvec3 extent = (b.hi - b.lo) + dvec3(2 * pad);
  for (int a = 0; a < 3; ++a) g.dims[a] = int(std::min(std::ceil(extent[a] / voxel) + 1.0, 1e9));
}

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t(std::min(a, b)) << 32) | std::max(a, b); }

// The angle-weighted pseudo-normals: each face's unit normal, each edge's sum of its faces'
// normals, each vertex's sum of its faces' normals weighted by the face's angle there.
struct PseudoNormals {
  std::vector<dvec3> face, vertex;
  std::unordered_map<uint64_t, dvec3> edge;
  std::unordered_map<uint64_t, int> uses;  // faces per edge
};

PseudoNormals pseudo_normals(const SurfaceMesh& mesh) {
  PseudoNormals n;
  n.face.resize(mesh.triangles.size());
  n.vertex.assign(mesh.positions.size(), dvec3(0.0));
  n.edge.reserve(mesh.triangles.size() * 2);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const glm::uvec3 t = mesh.triangles[f];
    const dvec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const dvec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double len = glm::length(c);
    n.face[f] = len > 0 ? c / len : dvec3(0.0);
    for (int k = 0; k < 3; ++k) {
      const dvec3 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      const double l1 = glm::length(e1), l2 = glm::length(e2);
      const double angle = l1 > 0 && l2 > 0 ? std::acos(std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0, 1.0)) : 0.0;
      n.vertex[t[k]] += angle * n.face[f];
      const uint64_t key = edge_key(t[k], t[(k + 1) % 3]);
      n.edge[key] += n.face[f];
      ++n.uses[key];
    }
  }
  return n;
}

}  // namespace

dvec3 closest_point_on_triangle(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c, int& feature) {
  const dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) { feature = 1; return a; }
  const dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) { feature = 2; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { feature = 4; return a + ab * (d1 / (d1 - d3)); }
  const dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) { feature = 3; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { feature = 6; return a + ac * (d2 / (d2 - d6)); }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    feature = 5;
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denom = 1.0 / (va + vb + vc);
  feature = 0;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double sdf_nodes(const SurfaceMesh& mesh, double voxel) {
  SdfGrid g;
  place_grid(mesh, voxel, g);
  return double(g.dims.x) * double(g.dims.y) * double(g.dims.z);
}

SdfGrid build_sdf(const SurfaceMesh& mesh, double voxel) {
  if (mesh.triangles.empty()) throw std::invalid_argument("build_sdf: a mesh without triangles");
  SdfGrid g;
  place_grid(mesh, voxel, g);
  const size_t n = g.nodes();
  const int nx = g.dims.x, ny = g.dims.y, nz = g.dims.z;
  auto index = [&](int x, int y, int z) { return g.index(x, y, z); };
  PseudoNormals pn = pseudo_normals(mesh);
  for (const auto& [key, count] : pn.uses) g.boundary_edges += count == 1;
  // A mesh wound inside out (clockwise seen from outside: its enclosed volume negative) gets
  // its normals turned round, so that the inside is where a user expects it.
  double volume = 0;
  for (const glm::uvec3& t : mesh.triangles)
    volume += glm::dot(mesh.positions[t[0]], glm::cross(mesh.positions[t[1]], mesh.positions[t[2]]));
  if (volume < 0) {
    for (auto& n : pn.face) n = -n;
    for (auto& n : pn.vertex) n = -n;
    for (auto& [key, n] : pn.edge) n = -n;
  }
  g.closed = g.boundary_edges == 0;

  // Exact distance at every node within the band of a triangle: each triangle visits the
  // nodes of its bounding box grown by the band (the nearest triangle wins; ties keep the first).
  std::vector<double> dist2(n, std::numeric_limits<double>::infinity());
  std::vector<int32_t> nearest(n, -1);
  const double band2 = g.band * g.band;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const glm::uvec3 t = mesh.triangles[f];
    const dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const dvec3 lo = (glm::min(a, glm::min(b, c)) - dvec3(g.band) - g.min) / voxel;
    const dvec3 hi = (glm::max(a, glm::max(b, c)) + dvec3(g.band) - g.min) / voxel;
    glm::ivec3 i0, i1;
    for (int k = 0; k < 3; ++k) {
      i0[k] = std::max(0, int(std::ceil(lo[k])));
      i1[k] = std::min(g.dims[k] - 1, int(std::floor(hi[k])));
    }
    for (int z = i0.z; z <= i1.z; ++z)
      for (int y = i0.y; y <= i1.y; ++y)
        for (int x = i0.x; x <= i1.x; ++x) {
          const dvec3 p = g.min + dvec3(x, y, z) * voxel;
          int feature;
          const dvec3 q = closest_point_on_triangle(p, a, b, c, feature);
          const dvec3 e = p - q;
          const double d2 = glm::dot(e, e);
          const size_t k = index(x, y, z);
          if (d2 < band2 && d2 < dist2[k]) {
            dist2[k] = d2;
            nearest[k] = int32_t(f);
          }
        }
  }

  g.values.assign(n, float(g.band));
  if (!g.closed) {  // an open surface: the distance, signed by the winding number
    sign_by_winding(mesh, g, nearest, dist2);
    return g;
  }
  // The band's sign: the pseudo-normal of the nearest feature (face, edge or vertex).
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const size_t k = index(x, y, z);
        if (nearest[k] < 0) continue;
        const glm::uvec3 t = mesh.triangles[size_t(nearest[k])];
        const dvec3 p = g.min + dvec3(x, y, z) * voxel;
        int feature;
        const dvec3 q = closest_point_on_triangle(p, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], feature);
        dvec3 normal;
        if (feature == 0) normal = pn.face[size_t(nearest[k])];
        else if (feature <= 3) normal = pn.vertex[t[feature - 1]];
        else normal = pn.edge.at(edge_key(t[feature - 4], t[(feature - 3) % 3]));
        const double d = std::sqrt(dist2[k]);
        g.values[k] = float(glm::dot(p - q, normal) < 0 ? -d : d);
      }
  // The far field: outside where a six-connected path of nodes outside the band reaches the
  // border, inside elsewhere.
  std::vector<uint8_t> outside(n, 0);
  std::vector<size_t> queue;
  auto seed = [&](int x, int y, int z) {
    const size_t k = index(x, y, z);
    if (nearest[k] < 0 && !outside[k]) {
      outside[k] = 1;
      queue.push_back(k);
    }
  };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        if (x == 0 || y == 0 || z == 0 || x == nx - 1 || y == ny - 1 || z == nz - 1) seed(x, y, z);
  while (!queue.empty()) {
    const size_t k = queue.back();
    queue.pop_back();
    const int x = int(k % size_t(nx)), y = int((k / size_t(nx)) % size_t(ny)), z = int(k / (size_t(nx) * size_t(ny)));
    if (x > 0) seed(x - 1, y, z);
    if (x < nx - 1) seed(x + 1, y, z);
    if (y > 0) seed(x, y - 1, z);
    if (y < ny - 1) seed(x, y + 1, z);
    if (z > 0) seed(x, y, z - 1);
    if (z < nz - 1) seed(x, y, z + 1);
  }
  for (size_t k = 0; k < n; ++k)
    if (nearest[k] < 0 && !outside[k]) g.values[k] = float(-g.band);
  return g;
}

double brute_force_distance(const SurfaceMesh& mesh, const dvec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const glm::uvec3& t : mesh.triangles) {
    int feature;
    const dvec3 q = closest_point_on_triangle(p, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], feature);
    best = std::min(best, glm::dot(p - q, p - q));
  }
  return std::sqrt(best);
}

double winding_number(const SurfaceMesh& mesh, const dvec3& p) {
  double sum = 0;  // each triangle's signed solid angle seen from p, every one visited
  for (const glm::uvec3& t : mesh.triangles)
    sum += triangle_winding(mesh.positions[t[0]] - p, mesh.positions[t[1]] - p, mesh.positions[t[2]] - p);
  return sum;
}

double brute_force_signed_distance(const SurfaceMesh& mesh, const dvec3& p) {
  const double d = brute_force_distance(mesh, p);
  return std::abs(winding_number(mesh, p)) > 0.5 ? -d : d;  // either winding
}

namespace {

// 64-bit FNV-1a, continued from `h`.
uint64_t fnv1a(uint64_t h, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

}  // namespace

uint64_t mesh_hash(const SurfaceMesh& mesh) {
  const uint64_t h = fnv1a(0xcbf29ce484222325ull, mesh.positions.data(), mesh.positions.size() * sizeof(dvec3));
  return fnv1a(h, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
}

namespace {

constexpr char kCacheMagic[16] = "clothsim sdf\n";
constexpr uint32_t kCacheVersion = 3;  // 2: a checksum after the grid; 3: open meshes signed by winding

struct CacheHeader {
  char magic[16];
  uint32_t version, closed;
  uint64_t hash;
  double voxel, band;
  double min[3];
  int32_t dims[3], pad;
  uint64_t boundary_edges;
};

}  // namespace

bool read_sdf_cache(const std::filesystem::path& file, uint64_t hash, double voxel, SdfGrid& out, std::string* problem) {
  std::string ignored;
  std::string& why = problem ? *problem : ignored;
  why.clear();
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(file, ec))) return false;  // none yet: not a problem
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(file, ec))) {
    why = "not a regular file";
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) return (why = "cannot be read", false);
  CacheHeader h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) return (why = "shorter than its header", false);
  if (std::memcmp(h.magic, kCacheMagic, sizeof kCacheMagic) != 0) return (why = "not a clothsim field", false);
  if (h.version != kCacheVersion) return (why = fmt::format("version {}, this clothsim writes {}", h.version, kCacheVersion), false);
  if (h.hash != hash || std::memcmp(&h.voxel, &voxel, sizeof voxel) != 0)
    return (why = "made from another mesh or spacing", false);
  SdfGrid g;
  g.min = dvec3(h.min[0], h.min[1], h.min[2]);
  g.voxel = h.voxel;
  g.band = h.band;
  g.dims = glm::ivec3(h.dims[0], h.dims[1], h.dims[2]);
  g.closed = h.closed != 0;
  g.boundary_edges = h.boundary_edges;
  if (g.dims.x < 2 || g.dims.y < 2 || g.dims.z < 2 || g.bytes() > kMaxSdfBytes) return (why = "a grid out of range", false);
  g.values.resize(g.nodes());
  uint64_t sum = 0;
  if (!in.read(reinterpret_cast<char*>(g.values.data()), std::streamsize(g.bytes())) ||
      !in.read(reinterpret_cast<char*>(&sum), sizeof sum))
    return (why = "truncated", false);
  if (in.peek() != std::char_traits<char>::eof()) return (why = "longer than its grid", false);
  // The checksum covers the header and every value: a flipped bit anywhere is caught, not only
  // one that makes a value NaN (a corrupted field once let a cloth fall through its collider).
  const uint64_t expected = fnv1a(fnv1a(0xcbf29ce484222325ull, &h, sizeof h), g.values.data(), g.bytes());
  if (sum != expected) return (why = "its checksum does not match its content", false);
  for (float v : g.values)
    if (!std::isfinite(v)) return (why = "holds a value that is not finite", false);
  out = std::move(g);
  return true;
}

void write_sdf_cache(const std::filesystem::path& file, uint64_t hash, const SdfGrid& g) {
  write_replacing(file.string(), [&](const std::string& temp) {
    std::ofstream o(temp, std::ios::binary);
    CacheHeader h{};
    std::memcpy(h.magic, kCacheMagic, sizeof kCacheMagic);
    h.version = kCacheVersion;
    h.closed = g.closed;
    h.hash = hash;
    h.voxel = g.voxel;
    h.band = g.band;
    for (int a = 0; a < 3; ++a) {
      h.min[a] = g.min[a];
      h.dims[a] = g.dims[a];
    }
    h.boundary_edges = g.boundary_edges;
    const uint64_t sum = fnv1a(fnv1a(0xcbf29ce484222325ull, &h, sizeof h), g.values.data(), g.bytes());
    o.write(reinterpret_cast<const char*>(&h), sizeof h);
    o.write(reinterpret_cast<const char*>(g.values.data()), std::streamsize(g.bytes()));
    o.write(reinterpret_cast<const char*>(&sum), sizeof sum);
    if (!o.flush()) throw std::runtime_error("could not write the SDF cache " + file.string());
  });
}

}  // namespace clothsim

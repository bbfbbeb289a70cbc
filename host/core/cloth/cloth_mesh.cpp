// A cloth from a mesh file as a builder of the cloth model (docs/model.md, "Mesh cloth"): the
// file's vertices become particles in its order, placed by scale, rotation and offset; quads
// keep the CS184 spring set and triangles get a stretch spring per edge and a bending spring
// across each interior edge (mesh_springs.hpp); each type is coloured greedily (colouring.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "cloth/cloth.hpp"
#include "cloth/colouring.hpp"
#include "cloth/mesh_import.hpp"
#include "cloth/mesh_springs.hpp"

namespace clothsim {
namespace {

// x' = R (scale x) + offset, R the rotation about the unit axis by the angle (Rodrigues).
glm::dvec3 place(const ClothParams& p, const glm::dvec3& x) {
  const double a = p.rotation_degrees * (3.14159265358979323846 / 180.0);
  const glm::dvec3 k = p.rotation_axis, v = x * p.scale;
  const double c = std::cos(a), s = std::sin(a);
  const glm::dvec3 kxv(k.y * v.z - k.z * v.y, k.z * v.x - k.x * v.z, k.x * v.y - k.y * v.x);
  const double kv = k.x * v.x + k.y * v.y + k.z * v.z;
  return v * c + kxv * s + k * (kv * (1 - c)) + p.offset;
}

// Where the file has no uv: the rest positions projected onto the plane of the two largest
// extents of their bounding box, scaled by the larger so a square texel stays square.
std::vector<glm::dvec2> planar_uv(const std::vector<glm::dvec3>& x) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (auto& p : x) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 size = hi - lo;
  int drop = 0;  // the axis of least extent
  for (int a = 1; a < 3; ++a)
    if (size[a] < size[drop]) drop = a;
  const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
  const double scale = std::max({size[u], size[v], 1e-12});
  std::vector<glm::dvec2> uv;
  for (auto& p : x) uv.push_back({(p[u] - lo[u]) / scale, (p[v] - lo[v]) / scale});
  return uv;
}

double triangle_area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 u = b - a, v = c - a;
  const glm::dvec3 n(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
  return 0.5 * std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
}

// simulation.seed > 0: every vertex moved along its area-weighted normal by the seeded hash,
// at most the grids' amplitude for the mean edge (jitter_amplitude), before the rest lengths
// are measured, so the perturbation is a shape, not a stress. `m.triangles` from `base` on are
// this mesh's.
void jitter_along_normals(const ClothModel& m, uint32_t base, uint32_t seed, std::vector<glm::dvec3>& x) {
  std::vector<glm::dvec3> normal(x.size(), glm::dvec3(0.0));
  double edges = 0;
  size_t count = 0;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    if (tri[0] < base) continue;
    const glm::dvec3 &a = x[tri[0] - base], &b = x[tri[1] - base], &c = x[tri[2] - base];
    const glm::dvec3 n = glm::cross(b - a, c - a);  // twice the area along the normal
    for (uint32_t v : tri) normal[v - base] += n;
    edges += glm::length(b - a) + glm::length(c - b) + glm::length(a - c);
    count += 3;
  }
  if (count == 0) return;
  const double amplitude = jitter_amplitude(edges / double(count));
  for (size_t v = 0; v < x.size(); ++v) {
    const double len = glm::length(normal[v]);
    if (len > 0) x[v] += normal[v] / len * vertical_offset(uint32_t(v), amplitude, seed);
  }
}

}  // namespace

PartSprings append_mesh(ClothModel& m, const Scene& scene, const ClothParams& p, uint32_t material) {
  const std::string what = fmt::format("{}: cloth{}.mesh", scene.source,
                                        material == 0 ? std::string() : fmt::format("[{}]", material));
  const PolyMesh mesh = load_mesh(p.mesh_path, what);
  const uint32_t base = uint32_t(m.count()), n = uint32_t(mesh.positions.size());
  std::vector<glm::dvec3> x;
  for (auto& v : mesh.positions) x.push_back(place(p, v));
  const std::vector<glm::dvec2> uv = mesh.uv.empty() ? planar_uv(x) : mesh.uv;

  // Triangles, and the area each vertex stands for: a third of each triangle's, a quarter of
  // each quad's (its two triangles, split along v1-v3 keeping the file's winding).
  std::vector<double> area(n, 0.0);
  double total = 0;
  for (auto& f : mesh.faces) {
    if (f.size() == 3) {
      m.triangles.push_back({base + f[0], base + f[1], base + f[2]});
      const double a = triangle_area(x[f[0]], x[f[1]], x[f[2]]);
      for (uint32_t v : f) area[v] += a / 3;
      total += a;
    } else {
      m.triangles.push_back({base + f[0], base + f[1], base + f[3]});
      m.triangles.push_back({base + f[1], base + f[2], base + f[3]});
      const double a = triangle_area(x[f[0]], x[f[1]], x[f[3]]) + triangle_area(x[f[1]], x[f[2]], x[f[3]]);
      for (uint32_t v : f) area[v] += a / 4;
      total += a;
    }
  }
  const double mean = total / n;
  for (auto& a : area)
    // Uniform: the CS184 rule. A vertex no face uses (kept so indices stay the file's) falls
    // as a free mass of the mean share.
    a = p.mass_lumping == MassLumping::Uniform || a == 0 ? mean : a;

  std::vector<uint8_t> pinned(n, 0);
  for (size_t k = 0; k < p.pinned_vertices.size(); ++k) {
    const int v = p.pinned_vertices[k];
    if (v < 0 || uint32_t(v) >= n)
      throw SceneError(fmt::format("{}: cloth.pinned_vertices[{}]: vertex {} is out of range: {} has {} vertices "
                                   "(0 to {})", scene.source, k, v, p.mesh, n, n - 1));
    pinned[v] = 1;
  }
  if (p.pinned_box)
    for (uint32_t v = 0; v < n; ++v)
      if (p.pinned_box->contains(x[v])) pinned[v] = 1;

  if (const uint32_t seed = uint32_t(scene.simulation.seed); seed != 0) jitter_along_normals(m, base, seed, x);

  for (uint32_t v = 0; v < n; ++v) {
    m.initial.push_back(x[v]);
    m.uv.push_back(uv[v]);
    m.area.push_back(area[v]);
    m.pinned.push_back(pinned[v]);
    m.material.push_back(material);
    m.tangent_ends.push_back({base + v, base + v});
  }

  const MeshSprings ms = build_mesh_springs(mesh);
  PartSprings out;
  // The tangent along +u: the structural neighbours of least and greatest u.
  std::vector<double> lo(n, 0.0), hi(n, 0.0);
  auto add = [&](const std::vector<std::array<uint32_t, 2>>& list, SpringType type) {
    const std::vector<uint32_t> colour = greedy_colouring(list, n);
    for (size_t k = 0; k < list.size(); ++k) {
      const uint32_t i = list[k][0], j = list[k][1];
      out.springs.push_back({base + i, base + j, glm::length(x[j] - x[i]), type, material});
      out.colour.push_back(colour[k]);
      if (type != SpringType::Structural) continue;
      for (auto [a, b] : {std::pair{i, j}, std::pair{j, i}}) {
        const double du = uv[b].x - uv[a].x;
        if (du < lo[a]) lo[a] = du, m.tangent_ends[base + a][0] = base + b;
        if (du > hi[a]) hi[a] = du, m.tangent_ends[base + a][1] = base + b;
      }
    }
  };
  add(ms.structural, SpringType::Structural);
  add(ms.shearing, SpringType::Shearing);
  add(ms.bending, SpringType::Bending);
  for (const Spring& s : out.springs)
    if (!(s.rest > 0))
      throw SceneError(fmt::format("{}: {}: vertices {} and {} coincide (a spring of rest length 0)", what, p.mesh,
                                   s.i - base, s.j - base));
  return out;
}

}  // namespace clothsim

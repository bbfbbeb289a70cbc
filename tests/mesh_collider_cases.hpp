// Shapes for the mesh-collider tests (test_mesh_colliders.cpp and its GPU twin): a cube, an
// icosphere and a torus, as triangle meshes written to OBJ files, each with its analytic depth
// (how far a point is inside the exact shape; negative outside), and a cloth dropped onto one.
#pragma once

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "scene/scene.hpp"
#include "colliders/sdf.hpp"
#include "test_helpers.hpp"

namespace clothsim::test {

// Centred at the origin: the tests place them with the collider's `origin`.
inline SurfaceMesh cube_mesh(double half) {
  SurfaceMesh m;
  for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? half : -half, k & 2 ? half : -half, k & 4 ? half : -half});
  // Two triangles per face, counter-clockwise seen from outside.
  const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

inline SurfaceMesh icosphere_mesh(double radius, int subdivisions) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  SurfaceMesh m;
  for (glm::dvec3 p : {glm::dvec3(-1, t, 0), {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t}, {0, -1, -t},
                       {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    m.positions.push_back(glm::normalize(p));
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto middle = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      return mid[key] = unsigned(m.positions.size() - 1);
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& f : m.triangles) {
      const unsigned ab = middle(f[0], f[1]), bc = middle(f[1], f[2]), ca = middle(f[2], f[0]);
      next.insert(next.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    m.triangles = next;
  }
  for (auto& p : m.positions) p *= radius;
  return m;
}

// About the y axis: the tube's centre circle has radius `ring`, the tube radius `tube`.
inline SurfaceMesh torus_mesh(double ring, double tube, int around, int across) {
  SurfaceMesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const double u = 2 * pi * i / around, v = 2 * pi * j / across;
      const double r = ring + tube * std::cos(v);
      m.positions.push_back({r * std::cos(u), tube * std::sin(v), r * std::sin(u)});
    }
  auto at = [&](int i, int j) { return unsigned(((i + around) % around) * across + (j + across) % across); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  return m;
}

inline void write_obj(const SurfaceMesh& m, const std::string& path) {
  std::ofstream o(path);
  o.precision(17);
  for (auto& p : m.positions) o << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (auto& t : m.triangles) o << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

struct Shape {
  std::string name;
  SurfaceMesh mesh;
  double (*depth)(const glm::dvec3& local);  // > 0 inside the exact shape, by how much
};

inline double cube_depth(const glm::dvec3& p) {
  const double h = 0.15;
  return std::min({h - std::abs(p.x), h - std::abs(p.y), h - std::abs(p.z)});
}
inline double sphere_depth(const glm::dvec3& p) { return 0.2 - glm::length(p); }
inline double torus_depth(const glm::dvec3& p) {
  const double q = std::sqrt(p.x * p.x + p.z * p.z) - 0.22;
  return 0.08 - std::sqrt(q * q + p.y * p.y);
}

inline std::vector<Shape> shapes() {
  return {{"cube", cube_mesh(0.15), cube_depth},
          {"icosphere", icosphere_mesh(0.2, 4), sphere_depth},
          {"torus", torus_mesh(0.22, 0.08, 96, 32), torus_depth}};
}

// Where the shapes sit: under the middle of the 0.6 m cloth, which falls from y = 1; under
// the middle of a cloth of another size at shape_at(size).
inline const glm::dvec3 kShapeAt{0.3, 0.5, 0.3};
inline glm::dvec3 shape_at(double size) { return {size / 2, kShapeAt.y, size / 2}; }

// A cloth of 13 x 13 masses, `size` square (centred over the shape), dropped from y 1 onto the
// mesh in `obj` at kShapeAt.
inline Scene drop_onto_mesh(const std::string& obj, const std::string& solver, const std::string& mesh_extra = "",
                            std::vector<std::string> sets = {}, double size = 0.6) {
  const glm::dvec3 at = shape_at(size);
  sets.insert(sets.end(), {fmt::format("cloth.width={}", size), fmt::format("cloth.height={}", size),
                           "simulation.self_collision=false",
                           fmt::format("simulation.solver=\"{}\"", solver)});
  if (solver == "fabric") sets.push_back("cloth.density=0.15");  // fabric at a fabric's density
  return make_scene(13, 13, 0, sets,
                    fmt::format(R"(, "mesh": {{"file": "{}", "origin": [{}, {}, {}], "friction": 0.3{}}})", obj,
                                at.x, at.y, at.z, mesh_extra));
}

}  // namespace clothsim::test

// Bending in physical units (issue 44; docs/materials.md): the flat stencils' rows against a
// cylinder's closed form on grids and meshes, and the cantilever on a mesh cloth (the plate
// fitted to each vertex's ring, host/core/cloth/mesh_plate.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "material_fixtures.hpp"
#include "mesh_fixtures.hpp"

using namespace clothsim;
using test::run;
using test::strip;

namespace {

using V3 = glm::dvec3;

// 1/2 x^T Q x over the model's bending rows at positions x (ClothModel::bend), with the rows'
// own checks: each sums to 0 (a translation costs nothing) and Q is symmetric.
double bending_energy(const ClothModel& m, const std::vector<V3>& x) {
  std::map<std::pair<uint32_t, uint32_t>, double> q;
  double energy = 0;
  for (uint32_t i = 0; i + 1 < m.bend_start.size(); ++i) {
    double sum = 0, scale = 0;
    for (uint32_t e = m.bend_start[i]; e < m.bend_start[i + 1]; ++e) {
      const BendEntry& b = m.bend[e];
      sum += b.weight;
      scale += std::abs(b.weight);
      if (b.other != i || e == m.bend_start[i]) q[{i, b.other}] += b.weight;
      energy += 0.5 * glm::dot(x[i], x[b.other]) * b.weight;
    }
    CHECK(std::abs(sum) <= 1e-12 * scale);
  }
  for (const auto& [ij, w] : q) {
    const auto other = q.find({ij.second, ij.first});
    REQUIRE(other != q.end());
    CHECK(std::abs(other->second - w) <= 1e-12 * std::abs(w));
  }
  return energy;
}

// The flat rest shape (in y = 0) wrapped isometrically round a cylinder of radius r through
// (0, r, 0): its curvature 1/r across x (axis along z), or across z (axis along x).
std::vector<V3> wrapped(const ClothModel& m, double r, bool across_x) {
  std::vector<V3> x;
  for (const glm::dvec3& p : m.initial) {
    const double s = across_x ? p.x : p.z, y = r * (1 - std::cos(s / r)), t = r * std::sin(s / r);
    x.push_back(across_x ? V3(t, y, p.z) : V3(p.x, y, t));
  }
  return x;
}

// A flat mesh cloth (the OBJ at `path`) of isotropic bending 1e-5 N·m wrapped round a cylinder
// of radius r, across x or z: its rows' energy over the closed form B k^2 / 2 times its area.
double wrapped_mesh_ratio(const std::string& path, double r, bool across_x) {
  const Scene scene = parse_scene(fmt::format(R"({{"cloth": {{"mesh": "{}", "thickness": 0.004,
      "material": {{"density": 0.2, "stretch": 2000, "shear": 20, "bending": 1e-5}}}},
      "simulation": {{"solver": "fabric"}}}})", path), "<mesh>");
  const ClothModel m = build_cloth(scene);
  double area = 0;
  for (const auto& t : m.triangles)
    area += 0.5 * glm::length(glm::cross(m.initial[t[1]] - m.initial[t[0]], m.initial[t[2]] - m.initial[t[0]]));
  return bending_energy(m, wrapped(m, r, across_x)) / (0.5 * 1e-5 / (r * r) * area);
}

}  // namespace

// A bend of curvature k costs B k^2 / 2 per area, B the rigidity across the bend (docs/materials.md):
// a grid wrapped round a cylinder across its warp and then its weft, and an irregular mesh (a
// disc with a hole, no texture: isotropic). The wrap is isometric: the rows see a pure bend.
TEST_CASE("A flat cloth's bending rows cost B k^2 / 2 per area wrapped round a cylinder", "[materials]") {
  const double r = 0.3, warp = 2e-5, weft = 5e-6, h = 0.01;
  const int n = 41;
  Scene scene = strip(n, n, h, "[0,0]", V3(0, -9.81, 0), "2000", 20, 1e-6);
  scene.cloth.material->bending = {warp, weft};
  const ClothModel grid = build_cloth(scene);
  for (bool across_x : {true, false}) {
    // The stencils of the curvature along the bend skip the two edge lines' half cells.
    const double area = ((n - 1) * h - h) * (n - 1) * h;
    const double expect = 0.5 * (across_x ? warp : weft) / (r * r) * area;
    const double got = bending_energy(grid, wrapped(grid, r, across_x));
    INFO((across_x ? "warp" : "weft") << ": " << got << " J, closed form " << expect << " J");
    CHECK(std::abs(got / expect - 1) < 0.01);
  }
  const std::string mesh = (std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "scenes/meshes/disc_hole.obj").string();
  for (bool across_x : {true, false}) {
    const double ratio = wrapped_mesh_ratio(mesh, r, across_x);
    INFO("mesh, across " << (across_x ? "x" : "z") << ": " << ratio << " times the closed form");
    CHECK(std::abs(ratio - 1) < 0.05);
  }
}

namespace {

// A strip as a mesh of near-equilateral triangles (every other row shifted by half a spacing,
// with its ends at 0 and `length` and a vertex at `clamp`, so that every row is held up to the
// clamp's edge), in y = 0, x along the strip (the warp, texture u), z across.
std::string strip_mesh(double length, double width, int along, double clamp, bool uv = true) {
  const double h = length / along;
  const int rows = std::max(2, int(std::lround(width / (h * 0.866)))) + 1;
  std::vector<std::vector<std::pair<double, int>>> row{size_t(rows)};
  std::string v, f;
  int count = 0;
  for (int r = 0; r < rows; ++r) {
    std::vector<double> xs;
    for (int i = 0; i <= along; ++i) xs.push_back(r % 2 && i > 0 ? (i - 0.5) * h : i * h);
    if (r % 2) xs.push_back(length);
    if (r % 2) xs.insert(std::upper_bound(xs.begin(), xs.end(), clamp), clamp);
    const double z = width * r / (rows - 1);
    for (double x : xs) {
      v += uv ? fmt::format("v {} 0 {}\nvt {} {}\n", x, z, x / length, z / width) : fmt::format("v {} 0 {}\n", x, z);
      row[size_t(r)].push_back({x, ++count});
    }
  }
  for (size_t r = 0; r + 1 < row.size(); ++r) {  // merge two rows by x, as scripts/drape-test merges rings
    const auto &a = row[r], &b = row[r + 1];
    size_t i = 0, j = 0;
    while (i + 1 < a.size() || j + 1 < b.size()) {
      const bool take_a = j + 1 >= b.size() || (i + 1 < a.size() && a[i + 1].first <= b[j + 1].first);
      const int p = a[i].second, q = b[j].second, next = take_a ? a[++i].second : b[++j].second;
      f += uv ? fmt::format("f {0}/{0} {1}/{1} {2}/{2}\n", p, next, q) : fmt::format("f {} {} {}\n", p, next, q);
    }
  }
  return v + f;
}

}  // namespace

// The cantilever again on a mesh cloth (the plate fitted to each vertex's ring, mesh_plate.cpp):
// the same chord at three resolutions, on triangles whose edges run three ways.
TEST_CASE("A mesh strip of bending rigidity B droops to Peirce's 41.5° chord at three resolutions", "[materials][slow]") {
  const double w = 0.2 * 9.81, b = 1e-5, l = 2 * std::cbrt(b / w);
  test::TempDir dir;
  for (int along : {8, 12, 16}) {
    const double h = l / along, clamp = std::round(0.02 / h) * h, length = clamp + l;
    const int total = int(std::lround(length / h));
    const auto path = dir.write(fmt::format("strip{}.obj", along), strip_mesh(length, 0.025, total, clamp));
    const Scene probe = parse_scene(fmt::format(R"({{"cloth": {{"mesh": "{}", "thickness": 0.001,
        "material": {{"density": 0.2, "stretch": 2000, "shear": 20, "bending": {}}}}},
        "simulation": {{"solver": "fabric"}}}})", path.string(), b), "<probe>");
    const ClothModel shape = build_cloth(probe);
    std::string pins;
    for (int i = 0; i < shape.count(); ++i)
      if (shape.initial[size_t(i)].x <= clamp + 1e-9) pins += fmt::format("{}{}", pins.empty() ? "" : ",", i);
    const Scene scene = parse_scene(fmt::format(R"({{"cloth": {{"mesh": "{}", "thickness": 0.001, "offset": [0, 1, 0],
        "pinned_vertices": [{}], "damping": 0.5,
        "material": {{"density": 0.2, "stretch": 2000, "shear": 20, "bending": {}}}}},
        "simulation": {{"solver": "fabric", "self_collision": false}}}})", path.string(), pins, b), "<strip>");
    const State<double> s = run<double>(scene, 180);
    V3 tip(0.0);
    int tips = 0;
    for (int i = 0; i < shape.count(); ++i)
      if (shape.initial[size_t(i)].x >= length - 1e-9) {
        tip += V3(s.pos[size_t(i)]);
        ++tips;
      }
    tip /= double(tips);
    const double angle = std::atan2(1.0 - tip.y, tip.x - clamp) * 180 / M_PI;
    INFO(along << " spacings along the overhang: chord " << angle << "°");
    CHECK(std::abs(angle - 41.5) < 2.0);
  }
}


// A mesh without texture coordinates has no warp: each triangle's is its first edge, which
// point every way round a vertex. Its plate must still cost B k^2 / 2 per area (isotropic B).
TEST_CASE("A flat mesh without texture coordinates bends as an isotropic plate", "[materials]") {
  test::TempDir dir;
  const auto path = dir.write("plain.obj", strip_mesh(0.3, 0.2, 30, 0.0, false));
  for (bool across_x : {true, false}) {
    const double ratio = wrapped_mesh_ratio(path.string(), 0.3, across_x);
    INFO("across " << (across_x ? "x" : "z") << ": " << ratio << " times the closed form");
    CHECK(std::abs(ratio - 1) < 0.02);
  }
}

// Cloth from a mesh file: load_mesh's vertex order per format, welding, errors and clean-up
// (the springs and their colouring: test_mesh_springs.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "cloth/colouring.hpp"
#include "mesh_fixtures.hpp"
#include "cloth/mesh_import.hpp"
#include "cloth/mesh_springs.hpp"
#include "scene/scene.hpp"

using namespace clothsim;
namespace fs = std::filesystem;
using test::all_springs;
using test::Grid;
using test::Pairs;
using test::TempDir;

namespace {

const std::string kWhat = "scenes/test.json: cloth.mesh";

// The message starts "<what>: <file>: " and contains the phrase. (One matcher object: Catch2
// v2's `a && b` keeps pointers to its operands, which must outlive it.)
struct MessageMatcher : Catch::MatcherBase<std::string> {
  std::string prefix, phrase;
  MessageMatcher(std::string prefix_, std::string phrase_) : prefix(std::move(prefix_)), phrase(std::move(phrase_)) {}
  bool match(const std::string& message) const override {
    return message.rfind(prefix, 0) == 0 && message.find(phrase) != std::string::npos;
  }
  std::string describe() const override { return "starts with \"" + prefix + "\" and contains \"" + phrase + "\""; }
};

}  // namespace

TEST_CASE("A quad grid OBJ loads in file order, its quads kept as quads, its uv read", "[mesh]") {
  TempDir dir;
  const Grid g(7, 5);
  const PolyMesh m = load_mesh(dir.write("grid.obj", g.obj()), kWhat);
  REQUIRE(m.positions.size() == 35);
  for (size_t i = 0; i < 35; ++i) CHECK(m.positions[i] == g.positions[i]);  // exactly as written (%.17g)
  REQUIRE(m.faces.size() == 24);
  CHECK(m.faces == g.faces);  // quads, in the file's winding
  REQUIRE(m.uv.size() == 35);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {  // Assimp keeps uv as floats
      CHECK(m.uv[size_t(y * 7 + x)].x == Approx(x / 6.0).margin(1e-7));
      CHECK(m.uv[size_t(y * 7 + x)].y == Approx(y / 4.0).margin(1e-7));
    }
}

TEST_CASE("Shuffled faces do not change the vertex order of an OBJ", "[mesh]") {
  TempDir dir;
  const Grid g(7, 5, 1.3, 0.7);
  std::vector<size_t> order(g.faces.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::shuffle(order.begin(), order.end(), std::mt19937(12345));
  const PolyMesh m = load_mesh(dir.write("shuffled.obj", g.obj(order)), kWhat);
  CHECK(m.positions == g.positions);
  REQUIRE(m.faces.size() == order.size());
  for (size_t f = 0; f < order.size(); ++f) CHECK(m.faces[f] == g.faces[order[f]]);
}

TEST_CASE("An OBJ vertex no face uses stays a particle; a uv seam is one particle with the first uv", "[mesh]") {
  TempDir dir;
  // v 3 (1-based) is used by no face; v 2 and v 5 carry two uv each (a seam).
  const PolyMesh m = load_mesh(dir.write("seam.obj",
                                         "v 0 0 0\nv 1 0 0\nv 5 5 5\nv 0 0 1\nv 1 0 1\nv 2 0 0\n"
                                         "vt 0 0\nvt 0.5 0\nvt 0 1\nvt 0.5 1\nvt 0.25 0\nvt 0.25 1\nvt 1 0\n"
                                         "f 2/5 6/7 5/6\nf 1/1 2/2 5/4 4/3\n"),
                               kWhat);
  REQUIRE(m.positions.size() == 6);
  CHECK(m.positions[2] == glm::dvec3(5, 5, 5));
  CHECK(m.faces == std::vector<std::vector<uint32_t>>{{1, 5, 4}, {0, 1, 4, 3}});
  REQUIRE(m.uv.size() == 6);
  CHECK(m.uv[1].x == Approx(0.25));  // the first face met gave v 2 the uv 0.25, not 0.5
  CHECK(m.uv[2] == glm::dvec2(0.0));  // unused: no uv
  const MeshSprings s = build_mesh_springs(m);
  for (auto [a, b] : all_springs(s)) CHECK((a != 2 && b != 2));
}

TEST_CASE("Several objects of one OBJ make one cloth in the file's vertex order", "[mesh]") {
  TempDir dir;
  // Assimp makes a mesh per object ("second", "third"), in the order of their faces.
  const PolyMesh m = load_mesh(dir.write("objects.obj",
                                         "o first\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
                                         "o second\nv 3 0 0\nv 4 0 0\nv 4 0 1\nv 3 0 1\nf 5 6 7 8\n"
                                         "o third\nf 1 2 3 4\n"),
                               kWhat);
  REQUIRE(m.positions.size() == 8);
  for (uint32_t i = 0; i < 8; ++i) CHECK(m.positions[i].x == double(i < 4 ? (i == 1 || i == 2) : 3 + (i == 5 || i == 6)));
  CHECK(m.faces == std::vector<std::vector<uint32_t>>{{4, 5, 6, 7}, {0, 1, 2, 3}});
  CHECK(m.uv.empty());
}

TEST_CASE("scripts/make-mesh grid writes the CS184 grid's positions bit for bit", "[mesh]") {
  if (std::system("/usr/bin/python3 -c 1 >/dev/null 2>&1") != 0) {
    WARN("no /usr/bin/python3: scripts/make-mesh not checked");
    return;
  }
  TempDir dir;
  const fs::path out = dir.path / "made.obj";
  const std::string command = fmt::format("/usr/bin/python3 '{}/scripts/make-mesh' grid '{}' --nw 7 --nh 5 --width 1.3 --height 0.7 >/dev/null",
                                          CLOTHSIM_SOURCE_DIR, out.string());
  REQUIRE(std::system(command.c_str()) == 0);
  const Grid g(7, 5, 1.3, 0.7);
  const PolyMesh m = load_mesh(out, kWhat);
  CHECK(m.positions == g.positions);
  CHECK(m.faces == g.faces);
}

TEST_CASE("The annulus loads: one hole, every triangle facing +y", "[mesh]") {
  const PolyMesh m = load_mesh(fs::path(CLOTHSIM_SOURCE_DIR) / "scenes/meshes/disc_hole.obj", kWhat);
  CHECK(m.positions.size() == 421);  // scenes/meshes/README.md
  CHECK(m.positions[0] == glm::dvec3(0.15, 0, 0));
  REQUIRE(m.uv.size() == m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const double r = std::hypot(m.positions[i].x, m.positions[i].z);
    CHECK((r > 0.15 - 1e-6 && r < 0.5 + 1e-6 && m.positions[i].y == 0));
    CHECK(m.uv[i].x == Approx(m.positions[i].x + 0.5).margin(1e-5));  // x/2R + 0.5 with R = 0.5
  }
  for (const auto& f : m.faces) {
    REQUIRE(f.size() == 3);
    const glm::dvec3 n = glm::cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]]);
    CHECK(n.y > 0);
  }
  // An annulus has V - E + F = 0; its edges are interior (one bending spring each) or on one
  // of the two boundary circles.
  const MeshSprings s = build_mesh_springs(m);
  CHECK(m.positions.size() + m.faces.size() == s.structural.size());
  const size_t boundary = s.structural.size() - s.bending.size();
  CHECK(boundary == 2 * s.structural.size() - 3 * m.faces.size());
}

TEST_CASE("load_mesh names the file and the problem", "[mesh]") {
  TempDir dir;
  auto error = [&](const fs::path& p, const char* phrase) { return MessageMatcher(kWhat + ": " + p.string() + ": ", phrase); };

  const fs::path missing = dir.path / "missing.obj";
  REQUIRE_THROWS_WITH(load_mesh(missing, kWhat), error(missing, "does not exist"));
  const fs::path text = dir.write("notes.txt", "These are some notes about the cloth.\nNo mesh here.\n");
  REQUIRE_THROWS_WITH(load_mesh(text, kWhat), error(text, "Assimp cannot read it: No suitable reader"));
  REQUIRE_THROWS_AS(load_mesh(text, kWhat), SceneError);
  const fs::path nan = dir.write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  REQUIRE_THROWS_WITH(load_mesh(nan, kWhat), error(nan, "vertex 0 (line 1) has a non-finite coordinate"));
  const fs::path fin = dir.write("fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  REQUIRE_THROWS_WITH(load_mesh(fin, kWhat), error(fin, "the edge between vertices 0 and 1 (0-based) is shared by more than two faces"));
  const fs::path points = dir.write("points.obj", "# only points\nv 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
  REQUIRE_THROWS_WITH(load_mesh(points, kWhat), error(points, "has no faces"));
  const fs::path bad_v = dir.write("bad_v.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n");
  REQUIRE_THROWS_WITH(load_mesh(bad_v, kWhat), error(bad_v, "line 2: a `v` line with 2 numbers"));
  const fs::path crlf = dir.write("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n\r\nf 1 2 3\r\nv 0 1 x\r\n");
  REQUIRE_THROWS_WITH(load_mesh(crlf, kWhat), error(crlf, "line 6: cannot read \"x\""));
}

TEST_CASE("Degenerate faces are dropped, polygons of 5 or more corners become fans", "[mesh]") {
  TempDir dir;
  // Face 2 is flat (three collinear corners), face 3 repeats a vertex.
  const PolyMesh m = load_mesh(dir.write("degenerate.obj",
                                         "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 2 0 0\n"
                                         "f 1 2 3\nf 1 2 5\nf 1 3 3\nf 1 3 4\n"),
                               kWhat);
  CHECK(m.faces == std::vector<std::vector<uint32_t>>{{0, 1, 2}, {0, 2, 3}});
  const PolyMesh pentagon = load_mesh(dir.write("pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 0 1\nv 1 0 2\nv -1 0 1\nf 1 2 3 4 5\n"), kWhat);
  CHECK(pentagon.faces == std::vector<std::vector<uint32_t>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}});
}

TEST_CASE("PLY, STL and glTF load in their own vertex order", "[mesh]") {
  TempDir dir;
  // PLY: the file's order, the unused vertex 4 kept, quads kept.
  const PolyMesh ply = load_mesh(dir.write("quad.ply",
                                           "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                                           "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                           "0 0 0\n1 0 0\n1 0 1\n0 0 1\n9 9 9\n2 0 0\n4 1 5 2 2\n4 0 1 2 3\n"),
                                 kWhat);
  // "4 1 5 2 2" repeats index 2: dropped as degenerate.
  REQUIRE(ply.positions.size() == 6);
  CHECK(ply.positions[4] == glm::dvec3(9, 9, 9));
  CHECK(ply.positions[5] == glm::dvec3(2, 0, 0));
  CHECK(ply.faces == std::vector<std::vector<uint32_t>>{{0, 1, 2, 3}});
  CHECK(ply.uv.empty());
  // STL: one vertex per facet corner, welded; the order of first appearance.
  const PolyMesh stl = load_mesh(dir.write("square.stl",
                                           "solid square\n"
                                           "facet normal 0 0 1\nouter loop\nvertex 1 1 0\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n"
                                           "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
                                           "endsolid square\n"),
                                 kWhat);
  CHECK(stl.positions == std::vector<glm::dvec3>{{1, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  CHECK(stl.faces == std::vector<std::vector<uint32_t>>{{0, 1, 2}, {1, 0, 3}});
  CHECK(build_mesh_springs(stl).bending.size() == 1);
  // glTF: the accessor's order, the node's translation applied, the unused vertex 4 kept.
  // Positions (0,0,0) (1,0,0) (1,0,1) (0,0,1) (9,9,9) as floats, then indices 2 1 0 3 2 0 (uint16).
  const std::string buffer =
      "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAAAAAAIA/AAAAAAAAAAAAAIA/AAAQQQAAEEEAABBBAgABAAAAAwACAAAA";
  const PolyMesh gltf = load_mesh(
      dir.write("square.gltf",
                R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,2,0]}],)"
                R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
                R"("buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" + buffer + R"("}],)"
                R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":60},{"buffer":0,"byteOffset":60,"byteLength":12}],)"
                R"("accessors":[{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3","min":[0,0,0],"max":[9,9,9]},)"
                R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]})"),
      kWhat);
  CHECK(gltf.positions == std::vector<glm::dvec3>{{0, 2, 0}, {1, 2, 0}, {1, 2, 1}, {0, 2, 1}, {9, 11, 9}});
  CHECK(gltf.faces == std::vector<std::vector<uint32_t>>{{2, 1, 0}, {3, 2, 0}});
}

TEST_CASE("A real model from assimp-testmodels loads in its file order", "[mesh]") {
  const fs::path wuson = "/usr/share/assimp/models/OBJ/WusonOBJ.obj";
  if (!fs::exists(wuson)) {
    WARN(wuson << " is not there (Debian's assimp-testmodels): skipped");
    return;
  }
  const PolyMesh m = load_mesh(wuson, kWhat);
  std::ifstream in(wuson);
  size_t v_lines = 0;
  std::string first_v;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("v ", 0) == 0 && v_lines++ == 0) first_v = line;
  CHECK(m.positions.size() == v_lines);
  double x = 0, y = 0, z = 0;
  REQUIRE(std::sscanf(first_v.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3);
  CHECK(m.positions[0] == glm::dvec3(x, y, z));
  CHECK(m.uv.size() == m.positions.size());
  const MeshSprings s = build_mesh_springs(m);
  const Pairs springs = all_springs(s);
  const std::vector<uint32_t> colour = greedy_colouring(springs, m.positions.size());
  CHECK(colouring_is_valid(springs, colour, m.positions.size()));
  WARN("WusonOBJ.obj: " << m.positions.size() << " particles, " << m.faces.size() << " faces, " << springs.size()
                        << " springs, " << colour_count(colour) << " colours");
}

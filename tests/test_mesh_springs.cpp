// The springs a mesh cloth gets (mesh_springs.hpp): a quad grid's are the CS184 grid's sets
// exactly, a triangle mesh's an edge each and bending across shared edges; and the greedy
// colouring of the springs (colouring.hpp): valid, deterministic, the one-at-a-time greedy, and
// few colours on the tablecloth.
#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "cloth/colouring.hpp"
#include "mesh_fixtures.hpp"
#include "cloth/mesh_import.hpp"
#include "cloth/mesh_springs.hpp"

using namespace clothsim;
using test::all_springs;
using test::Grid;
using test::Pairs;
using test::TempDir;
using test::unordered;
namespace fs = std::filesystem;

namespace {

const std::string kWhat = "scenes/test.json: cloth.mesh";

void check_grid_springs(const Grid& g, const MeshSprings& s) {
  const int nw = g.nw, nh = g.nh;
  CHECK(s.structural.size() == size_t((nw - 1) * nh + nw * (nh - 1)));
  CHECK(s.shearing.size() == size_t(2 * (nw - 1) * (nh - 1)));
  CHECK(s.bending.size() == size_t(std::max(nw - 2, 0) * nh + nw * std::max(nh - 2, 0)));
  CHECK(unordered(s.structural) == g.structural);
  CHECK(unordered(s.shearing) == g.shearing);
  CHECK(unordered(s.bending) == g.bending);
}

size_t max_degree(const Pairs& springs, size_t n) {
  std::vector<size_t> degree(n, 0);
  for (auto [a, b] : springs) ++degree[a], ++degree[b];
  return *std::max_element(degree.begin(), degree.end());
}

// The greedy colouring one spring at a time, the slow obvious way, to compare against.
std::vector<uint32_t> naive_greedy(const Pairs& springs, size_t n) {
  std::vector<std::set<uint32_t>> used(n);
  std::vector<uint32_t> colour;
  for (auto [a, b] : springs) {
    uint32_t c = 0;
    while (used[a].count(c) || used[b].count(c)) ++c;
    used[a].insert(c), used[b].insert(c);
    colour.push_back(c);
  }
  return colour;
}

}  // namespace

TEST_CASE("The springs of a quad grid are the CS184 grid's", "[mesh]") {
  TempDir dir;
  const Grid g(7, 5);
  const MeshSprings s = build_mesh_springs(load_mesh(dir.write("grid.obj", g.obj()), kWhat));
  check_grid_springs(g, s);
  // Discovery order: the first cell's edges A-B, B-D, D-C, C-A, then its diagonals A-D, B-C.
  REQUIRE(s.structural.size() >= 4);
  CHECK(s.structural[0] == std::array<uint32_t, 2>{0, 1});
  CHECK(s.structural[3] == std::array<uint32_t, 2>{7, 0});
  CHECK(s.shearing[0] == std::array<uint32_t, 2>{0, 8});
  CHECK(s.shearing[1] == std::array<uint32_t, 2>{1, 7});
  for (auto [nw, nh] : {std::pair{2, 2}, {3, 2}, {2, 5}, {3, 3}, {10, 4}, {16, 16}}) {
    INFO(nw << " x " << nh);
    const Grid h(nw, nh);
    check_grid_springs(h, build_mesh_springs(PolyMesh{h.positions, {}, h.faces}));
  }
}

TEST_CASE("Triangle mesh springs: an edge each, bending across shared edges", "[mesh]") {
  const std::vector<glm::dvec3> square{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  const MeshSprings s = build_mesh_springs(PolyMesh{square, {}, {{0, 1, 2}, {0, 2, 3}}});
  CHECK(s.structural.size() == 5);
  CHECK(s.shearing.empty());
  REQUIRE(s.bending.size() == 1);
  CHECK(s.bending[0] == std::array<uint32_t, 2>{1, 3});  // from the first face's opposite vertex
  // A quad and a triangle on one edge: that edge is one structural spring, no bending across it.
  const MeshSprings mixed = build_mesh_springs(PolyMesh{{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {2, 0, 0.5}}, {}, {{0, 1, 2, 3}, {1, 4, 2}}});
  CHECK(mixed.structural.size() == 6);
  CHECK(mixed.shearing.size() == 2);
  CHECK(mixed.bending.empty());
  CHECK_THROWS_AS(build_mesh_springs(PolyMesh{square, {}, {{0, 1, 7}}}), std::invalid_argument);
}

TEST_CASE("The greedy colouring is valid, deterministic and the one-at-a-time greedy", "[mesh]") {
  const Grid g(7, 5);
  const Pairs springs = all_springs(build_mesh_springs(PolyMesh{g.positions, {}, g.faces}));
  const std::vector<uint32_t> colour = greedy_colouring(springs, 35);
  CHECK(colouring_is_valid(springs, colour, 35));
  CHECK(greedy_colouring(springs, 35) == colour);
  CHECK(colour == naive_greedy(springs, 35));
  const size_t degree = max_degree(springs, 35);
  WARN("7x5 quad grid, all " << springs.size() << " springs: " << colour_count(colour) << " colours (max degree " << degree
                             << "; the grid's own scheme uses 12)");
  CHECK(colour_count(colour) >= degree);
  CHECK(colour_count(colour) <= 2 * degree - 1);
  std::vector<uint32_t> broken = colour;
  broken[1] = broken[0];  // springs 0 and 1 (0-1 and 1-8) share particle 1
  CHECK_FALSE(colouring_is_valid(springs, broken, 35));

  // More than 64 colours: the blocks of 64 give exactly the one-at-a-time result.
  std::mt19937 random(7);
  Pairs dense;
  for (int i = 0; i < 4000; ++i) {
    const uint32_t a = random() % 90, b = random() % 90;
    if (a != b) dense.push_back({a, b});
  }
  const std::vector<uint32_t> dense_colour = greedy_colouring(dense, 90);
  CHECK(colour_count(dense_colour) > 64);
  CHECK(colouring_is_valid(dense, dense_colour, 90));
  CHECK(dense_colour == naive_greedy(dense, 90));
  CHECK_THROWS_AS(greedy_colouring({{0, 5}}, 5), std::invalid_argument);
}

TEST_CASE("The tablecloth loads and its springs colour in few colours", "[mesh]") {
  const PolyMesh m = load_mesh(fs::path(CLOTHSIM_SOURCE_DIR) / "scenes/meshes/tablecloth.obj", kWhat);
  CHECK(m.positions.size() >= 10000);
  CHECK(m.positions[0] == glm::dvec3(0.0));  // the centre comes first (scenes/meshes/README.md)
  for (const auto& f : m.faces) REQUIRE(f.size() == 3);
  const MeshSprings s = build_mesh_springs(m);
  CHECK(s.shearing.empty());
  const size_t n = m.positions.size();
  // Euler: a disc has V - E + F = 1, and every interior edge has one bending spring.
  CHECK(n - s.structural.size() + m.faces.size() == 1);
  const Pairs springs = all_springs(s);
  const std::vector<uint32_t> colour = greedy_colouring(springs, n), edges = greedy_colouring(s.structural, n);
  CHECK(colouring_is_valid(springs, colour, n));
  CHECK(colouring_is_valid(s.structural, edges, n));
  CHECK(greedy_colouring(springs, n) == colour);
  const size_t degree = max_degree(springs, n), edge_degree = max_degree(s.structural, n);
  WARN("tablecloth: " << n << " vertices, " << m.faces.size() << " triangles, " << s.structural.size() << " structural + "
                      << s.bending.size() << " bending springs: " << colour_count(colour) << " colours for all (max degree "
                      << degree << "), " << colour_count(edges) << " for the structural alone (max degree " << edge_degree << ")");
  CHECK(colour_count(edges) >= edge_degree);
  CHECK(colour_count(colour) <= 2 * degree - 1);
}

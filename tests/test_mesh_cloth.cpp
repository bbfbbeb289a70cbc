// Mesh cloths (docs/model.md, "Mesh cloth"): a grid written as an OBJ of quads moves as the
// grid does, a triangulated disc with a hole hangs from its pinned box, several cloths make
// one model, every colouring is valid, and a bad mesh is a clear SceneError.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "backend.hpp"
#include "export/checkpoint.hpp"
#include "analysis/diagnostics.hpp"
#include "cloth/cloth.hpp"
#include "scene/scene.hpp"
#include "test_helpers.hpp"

namespace fs = std::filesystem;
using namespace clothsim;

namespace {

fs::path scratch_dir() {
  const fs::path d = fs::temp_directory_path() / fmt::format("clothsim_mesh_cloth_{}", ::getpid());
  fs::create_directories(d);
  return d;
}

// The quads of the CS184 horizontal grid, in its vertex order, positions exactly the grid's.
void write_grid_obj(const fs::path& file, int nw, int nh, double width, double height) {
  std::ofstream out(file);
  const double sx = width / (nw - 1), sy = height / (nh - 1);
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) out << fmt::format("v {:.17g} {:.17g} {:.17g}\n", x * sx, 1.0, y * sy);
  for (int y = 0; y + 1 < nh; ++y)
    for (int x = 0; x + 1 < nw; ++x) {
      const int a = y * nw + x + 1, b = a + 1, c = a + nw, d = c + 1;  // 1-based
      out << fmt::format("f {} {} {} {}\n", a, b, d, c);
    }
}

// Every colour's springs share no particle and are of one type.
void check_colouring(const ClothModel& m) {
  for (int c = 0; c < m.colours(); ++c) {
    std::set<uint32_t> used;
    for (uint32_t k = m.colour_start[c]; k < m.colour_start[c + 1]; ++k) {
      CHECK(used.insert(m.springs[k].i).second);
      CHECK(used.insert(m.springs[k].j).second);
      CHECK(m.springs[k].type == m.colour_type(c));
    }
  }
  CHECK(m.colour_start.back() == m.springs.size());
}

}  // namespace

TEST_CASE("a grid loaded from an OBJ of quads moves as the grid built from num_width_points", "[mesh]") {
  const fs::path dir = scratch_dir();
  const int nw = 7, nh = 5;
  write_grid_obj(dir / "grid.obj", nw, nh, 1.0, 1.0);
  const Scene grid = test::make_scene(nw, nh, 0, {"cloth.pinned=[[0,0],[6,0]]"});
  const std::string mesh_json = fmt::format(
      R"({{"cloth": {{"mesh": "{}", "thickness": 0.0095, "pinned_vertices": [0, 6], "mass_lumping": "uniform"}}}})",
      (dir / "grid.obj").string());
  const Scene mesh = parse_scene(mesh_json, (dir / "scene.json").string());
  const ClothModel gm = build_cloth(grid), mm = build_cloth(mesh);
  REQUIRE(mm.count() == gm.count());
  CHECK(mm.springs.size() == gm.springs.size());
  CHECK(mm.structural_springs() == gm.structural_springs());
  CHECK(mm.shearing_springs() == gm.shearing_springs());
  CHECK(mm.bending_springs() == gm.bending_springs());
  for (int i = 0; i < gm.count(); ++i) {
    CHECK(mm.initial[i] == gm.initial[i]);  // the file's vertex order is the particle order
    CHECK(mm.mass[i] == Approx(gm.mass[i]).epsilon(1e-12));
    CHECK(mm.pinned[i] == gm.pinned[i]);
  }
  check_colouring(mm);
  CpuBackend<double> a(grid, gm), b(mesh, mm);
  double worst = 0;
  for (int f = 0; f < 100; ++f) {
    a.step_frame();
    b.step_frame();
    worst = std::max(worst, test::max_abs_diff(a.snapshot().pos, b.snapshot().pos));
  }
  INFO("largest difference over 100 frames " << worst << " m");
  CHECK(worst <= 1e-6);
  // And they really moved: the comparison is not of two resting cloths.
  CHECK(test::max_abs_diff(a.snapshot().pos, CpuBackend<double>(grid, gm).snapshot().pos) > 0.1);
  fs::remove_all(dir);
}

// Issue 43, item 2: the same grid as an OBJ whose vertices are shuffled (vertex k of the file is
// grid particle perm[k]) gets the same coarse vertices and sweep colours, compared as positions,
// and under fabric the same motion: the hierarchy visits particles by rest position.
TEST_CASE("the same grid as a shuffled OBJ has the same hierarchy and colours and moves alike under fabric",
          "[mesh][multigrid]") {
  const fs::path dir = scratch_dir();
  const int nw = 21, nh = 21, n = nw * nh;
  const size_t count = size_t(n);
  std::vector<int> perm(count), slot(count);  // file vertex k is particle perm[k]; particle i is vertex slot[i]
  for (int k = 0; k < n; ++k) perm[size_t(k)] = int((uint64_t(k) * 7919u + 13u) % uint64_t(n));  // 7919 is prime to 441
  for (int k = 0; k < n; ++k) slot[size_t(perm[size_t(k)])] = k;
  {
    std::ofstream out(dir / "shuffled.obj");
    const double s = 1.0 / (nw - 1);
    for (int k = 0; k < n; ++k) out << fmt::format("v {:.17g} {:.17g} {:.17g}\n", (perm[size_t(k)] % nw) * s, 1.0, (perm[size_t(k)] / nw) * s);
    for (int y = 0; y + 1 < nh; ++y)
      for (int x = 0; x + 1 < nw; ++x) {
        const int a = y * nw + x, b = a + 1, c = a + nw, d = c + 1;
        out << fmt::format("f {} {} {} {}\n", slot[size_t(a)] + 1, slot[size_t(b)] + 1, slot[size_t(d)] + 1, slot[size_t(c)] + 1);
      }
  }
  const std::vector<std::string> fabric{"simulation.solver=\"fabric\"", "cloth.density=0.15", "cloth.ks=5000",
                                        "simulation.self_collision=false"};
  std::vector<std::string> grid_sets = fabric;
  grid_sets.push_back(fmt::format("cloth.pinned=[[0,0],[{},0]]", nw - 1));
  const Scene grid = test::make_scene(nw, nh, 0, grid_sets);
  const Scene mesh = parse_scene(
      fmt::format(R"({{"cloth": {{"mesh": "{}", "thickness": 0.0095, "density": 0.15, "ks": 5000, "pinned_vertices": [{}, {}],
                     "mass_lumping": "uniform"}}, "simulation": {{"solver": "fabric", "self_collision": false}}}})",
                  (dir / "shuffled.obj").string(), slot[0], slot[size_t(nw - 1)]),
      (dir / "scene.json").string());
  const ClothModel gm = build_cloth(grid), mm = build_cloth(mesh);
  REQUIRE(mm.count() == n);
  const Hierarchy gh = build_hierarchy(gm, {5000.0}), mh = build_hierarchy(mm, {5000.0});
  // A set of particles as the set of their rest positions.
  auto where = [](const ClothModel& m, auto first, auto last) {
    std::set<std::tuple<double, double, double>> out;
    for (auto it = first; it != last; ++it) out.insert({m.initial[*it].x, m.initial[*it].y, m.initial[*it].z});
    return out;
  };
  REQUIRE(gh.levels.size() == mh.levels.size());
  for (size_t l = 0; l < gh.levels.size(); ++l) {
    const HierarchyLevel &a = gh.levels[l], &b = mh.levels[l];
    REQUIRE(a.count == b.count);
    CHECK(where(gm, gh.particle.begin() + a.first, gh.particle.begin() + a.first + a.count) ==
          where(mm, mh.particle.begin() + b.first, mh.particle.begin() + b.first + b.count));
  }
  REQUIRE(gh.fine_colours() == mh.fine_colours());
  for (int c = 0; c < gh.fine_colours(); ++c)
    CHECK(where(gm, gh.fine_order.begin() + gh.fine_colour_start[size_t(c)], gh.fine_order.begin() + gh.fine_colour_start[size_t(c) + 1]) ==
          where(mm, mh.fine_order.begin() + mh.fine_colour_start[size_t(c)], mh.fine_order.begin() + mh.fine_colour_start[size_t(c) + 1]));
  CpuBackend<double> a(grid, gm), b(mesh, mm);
  for (int f = 0; f < 60; ++f) {
    a.step_frame();
    b.step_frame();
  }
  double worst = 0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, double(glm::length(glm::dvec3(a.snapshot().pos[size_t(i)]) - glm::dvec3(b.snapshot().pos[size_t(slot[size_t(i)])]))));
  INFO("largest distance between a grid particle and its mesh vertex after 60 frames: " << worst << " m");
  CHECK(worst <= 1e-6);
  CHECK(test::max_abs_diff(a.snapshot().pos, CpuBackend<double>(grid, gm).snapshot().pos) > 0.05);  // it moved
  fs::remove_all(dir);
}

TEST_CASE("a triangulated disc with a hole, pinned by pinned_box, hangs from its pins", "[mesh][long]") {
  const Scene s = load_scene(fs::path(CLOTHSIM_SOURCE_DIR) / "scenes/disc_hole.json");
  const ClothModel m = build_cloth(s);
  CHECK(m.count() == 421);
  CHECK(m.triangles.size() == 748);
  const int pins = int(std::count(m.pinned.begin(), m.pinned.end(), 1));
  CHECK(pins >= 2);
  CHECK(pins < 20);
  for (int i = 0; i < m.count(); ++i)
    if (m.pinned[i]) CHECK(m.initial[i].x >= 0.44);
  check_colouring(m);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < 90; ++f) cpu.step_frame();
  const ClothSnapshot snap = cpu.snapshot();
  const ClothStats st = measure(s, m, snap);
  CHECK(st.finite);
  double lowest = 1e9;
  for (int i = 0; i < m.count(); ++i) {
    lowest = std::min(lowest, snap.pos[i].y);
    if (m.pinned[i]) CHECK(glm::dvec3(snap.pos[i]) == m.initial[i]);
  }
  // A 1 m disc hanging from one edge: its far side falls most of a metre.
  CHECK(lowest < 0.3);
  CHECK(st.max_stretch_ratio < 1.1 + 1e-6);
}

TEST_CASE("the mesh scenes' colourings are valid: no two springs of a colour share a particle", "[mesh]") {
  for (const char* name : {"tablecloth", "two_cloths", "disc_hole"}) {
    INFO(name);
    const Scene s = load_scene(fs::path(CLOTHSIM_SOURCE_DIR) / "scenes" / (std::string(name) + ".json"));
    const ClothModel m = build_cloth(s);
    check_colouring(m);
    CHECK(m.colours() <= 20);
    // Deterministic: the same model twice.
    const ClothModel again = build_cloth(s);
    REQUIRE(again.springs.size() == m.springs.size());
    for (size_t k = 0; k < m.springs.size(); ++k) CHECK((again.springs[k].i == m.springs[k].i && again.springs[k].j == m.springs[k].j));
  }
}

TEST_CASE("a mesh cloth is placed by scale, rotation and offset, its mass from density x area", "[mesh]") {
  const fs::path dir = scratch_dir();
  {
    std::ofstream out(dir / "tri.obj");
    out << "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nf 1 3 2\nf 2 3 4\n";
  }
  const Scene s = parse_scene(
      R"({"cloth": {"mesh": "tri.obj", "thickness": 0.01, "density": 2, "scale": 2, "offset": [0, 1, 0],
          "rotation_axis": [0, 1, 0], "rotation_degrees": 90}})",
      (dir / "scene.json").string());
  const ClothModel m = build_cloth(s);
  REQUIRE(m.count() == 4);
  // (1, 0, 0) scaled to (2, 0, 0), turned 90 degrees about +y to (0, 0, -2), lifted by 1.
  CHECK(m.initial[1].x == Approx(0).margin(1e-12));
  CHECK(m.initial[1].y == Approx(1));
  CHECK(m.initial[1].z == Approx(-2));
  double total = 0;
  for (double mass : m.mass) total += mass;
  CHECK(total == Approx(2.0 * 4.0));  // density 2 x area (2 m)^2
  // Area lumping: the two corners of both triangles stand for more of the cloth.
  CHECK(m.mass[1] == Approx(2 * m.mass[0]));
  // Two triangles: five edges, one bending spring across the shared one.
  CHECK(m.structural_springs() == 5);
  CHECK(m.bending_springs() == 1);
  fs::remove_all(dir);
}

TEST_CASE("a pinned vertex outside the mesh is bad input naming the key and the range", "[mesh]") {
  const fs::path root = CLOTHSIM_SOURCE_DIR;
  const Scene s = load_scene(root / "scenes/disc_hole.json", {"cloth.pinned_vertices=[3, 421]"});
  CHECK_THROWS_WITH(build_cloth(s), Catch::Contains("cloth.pinned_vertices[1]") && Catch::Contains("vertex 421") &&
                                        Catch::Contains("421 vertices"));
}

TEST_CASE("two cloths (a grid and a mesh) save, load and continue bit for bit; a state fits only its cloth",
          "[mesh][checkpoint]") {
  const fs::path root = CLOTHSIM_SOURCE_DIR, dir = scratch_dir();
  const Scene s = load_scene(root / "scenes/two_cloths.json");
  const ClothModel m = build_cloth(s);
  const int n = 6;
  CpuBackend<double> whole(s, m);
  for (int f = 0; f < 2 * n; ++f) whole.step_frame();
  {
    CpuBackend<double> first(s, m);
    for (int f = 0; f < n; ++f) first.step_frame();
    write_checkpoint((dir / "half.state").string(),
                     {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, first.name(), first.save_state()});
  }
  const Checkpoint c = read_checkpoint((dir / "half.state").string());
  CHECK(c.nw * c.nh == m.count());  // a model of several cloths is stored as count x 1
  CpuBackend<double> second(s, m);
  check_fits(c, (dir / "half.state").string(), s, m, second.scalar_bytes(), second.name());
  second.load_state(c.state);
  for (int f = 0; f < n; ++f) second.step_frame();
  CHECK(whole.save_state().positions == second.save_state().positions);
  CHECK(whole.save_state().displacement == second.save_state().displacement);
  // The same particle count with other triangles is another cloth: the hash covers the mesh.
  ClothModel other = m;
  std::swap(other.triangles[0][0], other.triangles[0][1]);
  CHECK(cloth_hash(other) != cloth_hash(m));
  const Scene disc = load_scene(root / "scenes/disc_hole.json");
  CHECK_THROWS_WITH(check_fits(c, "half.state", disc, build_cloth(disc), 8, "cpu (double)"),
                    Catch::Contains("different cloth"));
  fs::remove_all(dir);
}

TEST_CASE("a mesh cloth exports as OBJ in its file's vertex order", "[mesh][export]") {
  const fs::path root = CLOTHSIM_SOURCE_DIR, dir = scratch_dir();
  const Scene s = load_scene(root / "scenes/disc_hole.json");
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < 3; ++f) cpu.step_frame();
  write_obj((dir / "out.obj").string(), m, cpu.snapshot());
  // The file's own vertices, placed as the scene places them (offset [0, 1, 0]).
  std::ifstream mesh(root / "scenes/meshes/disc_hole.obj"), out(dir / "out.obj");
  std::vector<glm::dvec3> file, exported;
  for (std::string line; std::getline(mesh, line);)
    if (line.rfind("v ", 0) == 0) {
      glm::dvec3 v;
      std::sscanf(line.c_str(), "v %lf %lf %lf", &v.x, &v.y, &v.z);
      file.push_back(v + glm::dvec3(0, 1, 0));
    }
  for (std::string line; std::getline(out, line);)
    if (line.rfind("v ", 0) == 0) {
      glm::dvec3 v;
      std::sscanf(line.c_str(), "v %lf %lf %lf", &v.x, &v.y, &v.z);
      exported.push_back(v);
    }
  REQUIRE(exported.size() == file.size());
  int pinned = 0;
  for (size_t i = 0; i < file.size(); ++i)
    if (m.pinned[i]) {  // pins have not moved: vertex i of the export is vertex i of the file
      ++pinned;
      CHECK(glm::length(exported[i] - file[i]) < 1e-6);
    }
  CHECK(pinned > 0);
  fs::remove_all(dir);
}

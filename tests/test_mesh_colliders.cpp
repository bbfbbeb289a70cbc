// Mesh colliders (docs/model.md, "Mesh colliders"): the signed distance field against a
// brute-force exact distance and winding number, cloths dropped onto a cube, a sphere and a
// torus against the exact shapes, the mesh sphere against the analytic sphere collider, the
// cache, and bad input.
#include <catch2/catch.hpp>

#include <random>

#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "colliders/mesh_collider.hpp"
#include "mesh_collider_cases.hpp"
#include "reference/reference_detail.hpp"

using namespace clothsim;

namespace {

// The field of `mesh` at the identity placement, as the collision pass samples it.
MeshColliderT<double> identity_collider(const SdfGrid& g) {
  MeshColliderT<double> m{};
  m.row0 = {1, 0, 0, 0};  // w: the origin
  m.row1 = {0, 1, 0, 0};
  m.row2 = {0, 0, 1, 0};
  m.grid = glm::dvec4(g.min, 1.0 / g.voxel);
  m.dims = glm::ivec4(g.dims, 0);
  return m;
}

}  // namespace

TEST_CASE("a mesh's signed distance field agrees with the exact distance in its band and has the right sign",
          "[mesh_collider][long]") {
  for (const test::Shape& shape : test::shapes()) {
    INFO(shape.name << ": " << shape.mesh.triangles.size() << " triangles");
    const SdfGrid g = build_sdf(shape.mesh, 0.01);
    CHECK(g.closed);
    CHECK(g.boundary_edges == 0);
    const MeshColliderT<double> m = identity_collider(g);
    std::mt19937_64 rng(7);
    const glm::dvec3 lo = g.min, hi = g.min + glm::dvec3(g.dims - 1) * g.voxel;
    std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
    int in_band = 0, wrong_sign = 0, far_off = 0;
    double worst = 0;
    for (int k = 0; k < 10000; ++k) {
      const glm::dvec3 p(ux(rng), uy(rng), uz(rng));
      double phi;
      glm::dvec3 grad;
      REQUIRE(sample_mesh_field(m, g.values.data(), p, phi, grad));
      const double exact = brute_force_signed_distance(shape.mesh, p);
      // The sign everywhere (but within half a node spacing of the surface, where the
      // interpolation may cross zero a little off the surface).
      if (std::abs(exact) > 0.5 * g.voxel && (phi < 0) != (exact < 0)) ++wrong_sign;
      if (std::abs(exact) < g.band - g.voxel) {
        ++in_band;
        worst = std::max(worst, std::abs(phi - exact));
        far_off += std::abs(phi - exact) > 0.5 * g.voxel;
      }
    }
    INFO(in_band << " of 10000 points in the band; worst |field - exact| " << worst << " m");
    CHECK(in_band > 500);
    CHECK(wrong_sign == 0);
    CHECK(far_off == 0);
  }
}

TEST_CASE("an open mesh gets an unsigned field: a shell with no inside", "[mesh_collider]") {
  // The icosphere without its top cap: open, and every node's value is the distance >= 0.
  SurfaceMesh cap = test::icosphere_mesh(0.2, 2);
  std::vector<glm::uvec3> kept;
  for (const glm::uvec3& t : cap.triangles)
    if (cap.positions[t[0]].y < 0.15 || cap.positions[t[1]].y < 0.15 || cap.positions[t[2]].y < 0.15) kept.push_back(t);
  cap.triangles = kept;
  const SdfGrid g = build_sdf(cap, 0.01);
  CHECK_FALSE(g.closed);
  CHECK(g.boundary_edges > 0);
  double lowest = 1;
  for (float v : g.values) lowest = std::min(lowest, double(v));
  CHECK(lowest >= 0);
  // At the centre the distance to the shell is its radius (beyond the band: clamped to it).
  const MeshColliderT<double> m = identity_collider(g);
  double phi;
  glm::dvec3 grad;
  REQUIRE(sample_mesh_field(m, g.values.data(), glm::dvec3(0.0), phi, grad));
  CHECK(phi == Approx(g.band));
}

TEST_CASE("an inside-out mesh has the same inside as the right way round", "[mesh_collider]") {
  SurfaceMesh flipped = test::cube_mesh(0.15);
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  const SdfGrid a = build_sdf(test::cube_mesh(0.15), 0.02), b = build_sdf(flipped, 0.02);
  REQUIRE(a.values.size() == b.values.size());
  // The same field but for the rounding of the closest points, whose corners come in another order.
  double worst = 0;
  for (size_t k = 0; k < a.values.size(); ++k) {
    CHECK((a.values[k] < 0) == (b.values[k] < 0));
    worst = std::max(worst, double(std::abs(a.values[k] - b.values[k])));
  }
  CHECK(worst < 1e-7);
}

TEST_CASE("a cloth dropped onto a mesh cube, sphere and torus never has a mass deeper than half a node + 0.1 mm "
          "inside the exact shape",
          "[mesh_collider][long]") {
  test::TempDir dir("mesh_colliders", "drop");
  for (const test::Shape& shape : test::shapes()) {
    const std::string obj = dir / (shape.name + ".obj");
    test::write_obj(shape.mesh, obj);
    for (const char* solver : {"classic", "xpbd"}) {
      INFO(shape.name << ", " << solver);
      const Scene s = test::drop_onto_mesh(obj, solver);
      const ClothModel model = build_cloth(s);
      CpuBackend<float> cpu(s, model);
      const double voxel = load_collider_mesh(s, 0)->sdf.voxel;
      double deepest = -1, lowest = 1;
      for (int f = 0; f < 90; ++f) {
        cpu.step_frame();
        for (const auto& p : cpu.state().pos) {
          deepest = std::max(deepest, shape.depth(glm::dvec3(p.x, p.y, p.z) - test::kShapeAt));
          lowest = std::min(lowest, double(p.y));
        }
      }
      INFO("deepest inside " << deepest << " m (node spacing " << voxel << " m); lowest mass at y " << lowest);
      CHECK(deepest <= 0.5 * voxel + 1e-4);
      // It rests on the shape: it did not fall past it.
      CHECK(lowest > 0.2);
    }
  }
}

TEST_CASE("a cloth on the mesh sphere rests within 2 mm of where it rests on the analytic sphere", "[mesh_collider][long]") {
  // A frictionless tent: the cloth pinned at its four corners at y 1 sags onto a sphere whose
  // top is 5 mm below them. Frictionless, its rest is one static equilibrium (with friction the rest depends
  // on the path, which a different contact normal a micrometre off changes), so the two
  // colliders must give the same rest to what the field's interpolation and the icosphere's
  // facets allow.
  test::TempDir dir("mesh_colliders", "sphere");
  const std::string obj = dir / "sphere.obj";
  test::write_obj(test::icosphere_mesh(0.2, 5), obj);
  const glm::dvec3 at(0.3, 0.795, 0.3);
  for (const char* solver : {"classic", "xpbd"}) {
    Scene on_mesh = test::drop_onto_mesh(obj, solver, R"(, "thickness": 0)",
                                         {"cloth.pinned=[[0,0],[12,0],[0,12],[12,12]]", "mesh.friction=0"});
    on_mesh.meshes[0].origin = at;
    Scene on_sphere = on_mesh;
    on_sphere.meshes.clear();
    on_sphere.spheres.push_back({at, 0.2, 0.0, std::nullopt});
    const ClothModel model = build_cloth(on_mesh);
    CpuBackend<double> a(on_mesh, model), b(on_sphere, model);
    for (int f = 0; f < 180; ++f) {
      a.step_frame();
      b.step_frame();
    }
    double worst = 0, fastest = 0;
    for (size_t i = 0; i < a.state().pos.size(); ++i) {
      worst = std::max(worst, glm::length(glm::dvec3(a.state().pos[i]) - glm::dvec3(b.state().pos[i])));
      fastest = std::max(fastest, glm::length(glm::dvec3(a.state().disp[i])) / on_mesh.dt());
    }
    INFO(solver << ": largest distance between the two rests " << worst << " m; fastest mass " << fastest << " m/s");
    CHECK(fastest < 0.01);  // at rest
    CHECK(worst <= 2e-3);
    // And it does rest on the sphere: its middle touches the top.
    CHECK(a.state().pos[6 * 13 + 6].y < at.y + 0.2 + 1e-4);
  }
}

TEST_CASE("a mass that goes through a mesh within one substep is caught on the side it came from",
          "[mesh_collider]") {
  // A 30 cm cube at kShapeAt; a mass ends 2 cm below it having come from 2 cm above it in one
  // substep (34 cm, far more than the 3-node band): its end is outside, its path is not. And
  // the same through an open shell (the cube without its face at z = -h): the mass stays on top.
  test::TempDir dir("mesh_colliders", "tunnel");
  SurfaceMesh open_box = test::cube_mesh(0.15);
  open_box.triangles.erase(open_box.triangles.begin(), open_box.triangles.begin() + 2);  // the face z = -h
  for (const auto& [name, mesh] : {std::pair{"cube", test::cube_mesh(0.15)}, std::pair{"open_box", open_box}}) {
    INFO(name);
    const std::string obj = dir / (std::string(name) + ".obj");
    test::write_obj(mesh, obj);
    for (const char* solver : {"classic", "xpbd"}) {
      const Scene s = test::drop_onto_mesh(obj, solver, R"(, "voxel_size": 0.01)");
      const ClothModel model = build_cloth(s);
      auto c = make_constants<double>(s, model);
      set_substep_time(c, 0.0);
      auto st = initial_state<double>(model);
      const glm::dvec3 below = test::kShapeAt + glm::dvec3(0.01, -0.17, 0.02);
      st.pos[5] = glm::dvec4(below, st.pos[5].w);
      st.disp[5] = glm::dvec4(0, -0.34, 0, 0);
      collide_objects(c, st);
      INFO(solver << ": the mass ends at y " << st.pos[5].y);
      CHECK(st.pos[5].y > test::kShapeAt.y + 0.15);
      CHECK(st.pos[5].y < test::kShapeAt.y + 0.2);
    }
  }
}

TEST_CASE("a field that took over a second is kept in a cache file and read back bit for bit", "[mesh_collider]") {
  test::TempDir dir("mesh_colliders", "cache");
  const SurfaceMesh mesh = test::torus_mesh(0.22, 0.08, 24, 12);
  const SdfGrid g = build_sdf(mesh, 0.02);
  const std::filesystem::path file = dir / "t.sdf";
  write_sdf_cache(file, mesh_hash(mesh), g);
  SdfGrid back;
  REQUIRE(read_sdf_cache(file, mesh_hash(mesh), 0.02, back));
  CHECK(test::mismatches(back.values, g.values) == 0);
  CHECK(back.dims == g.dims);
  CHECK(back.min == g.min);
  // Another spacing, or another mesh: not this field (rebuilt).
  CHECK_FALSE(read_sdf_cache(file, mesh_hash(mesh), 0.021, back));
  CHECK_FALSE(read_sdf_cache(file, mesh_hash(mesh) + 1, 0.02, back));
  CHECK_FALSE(read_sdf_cache(dir / "absent.sdf", mesh_hash(mesh), 0.02, back));
}

TEST_CASE("bad mesh colliders are refused naming the file, the key and what was expected", "[mesh_collider]") {
  test::TempDir dir("mesh_colliders", "bad");
  auto refused = [&](const std::string& mesh_json) {
    try {
      const Scene s = test::make_scene(5, 5, 0, {}, ", \"mesh\": " + mesh_json);
      const ClothModel m = build_cloth(s);
      (void)make_constants<float>(s, m);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string missing = dir / "missing.obj";
  CHECK_THAT(refused(fmt::format(R"({{"file": "{}"}})", missing)),
             Catch::Contains("mesh.file") && Catch::Contains("missing.obj"));
  const std::string lines = dir / "lines.obj";
  std::ofstream(lines) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n";
  CHECK_THAT(refused(fmt::format(R"({{"file": "{}"}})", lines)),
             Catch::Contains("mesh.file") && Catch::Contains("no faces"));
  const std::string cube = dir / "cube.obj";
  test::write_obj(test::cube_mesh(0.15), cube);
  CHECK_THAT(refused(fmt::format(R"({{"file": "{}", "voxel_size": 1e-5}})", cube)),
             Catch::Contains("mesh.voxel_size") && Catch::Contains("MiB") && Catch::Contains("at least"));
  CHECK_THAT(refused(fmt::format(R"({{"file": "{}", "origin": [0, 1e999, 0]}})", cube)),
             Catch::Contains("mesh.origin") && Catch::Contains("finite"));
  CHECK_THAT(refused(fmt::format(R"({{"file": "{}", "scale": 0}})", cube)), Catch::Contains("mesh.scale"));
  CHECK_THAT(refused(fmt::format(R"({{"file": "{}", "rotation_axis": [0, 0, 0]}})", cube)),
             Catch::Contains("mesh.rotation_axis"));
  CHECK_THAT(refused(fmt::format(R"([{{"file": "{}"}}, {{"file": "{}", "friction": 2}}])", cube, cube)),
             Catch::Contains("mesh[1].friction"));
  CHECK(refused(fmt::format(R"({{"file": "{}"}})", cube)) == "(accepted)");
}

// Mesh colliders (docs/model.md, "Mesh colliders"): the signed distance field against a
// brute-force exact distance and winding number, cloths dropped onto a cube, a sphere and a
// torus against the exact shapes, the mesh sphere against the analytic sphere collider, the
// cache, and bad input.
#include <catch2/catch.hpp>

#include <random>

#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "colliders/mesh_collider.hpp"
#include "colliders/winding.hpp"
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

TEST_CASE("an open mesh's field is signed by its winding number: a hole is closed, a sheet stays a shell", "[mesh_collider]") {
  // The icosphere without its top cap: open, yet its inside is kept (the level set of winding
  // number 1/2 closes the hole), and every node's sign is the exact winding number's.
  SurfaceMesh cap = test::icosphere_mesh(0.2, 2);
  std::vector<glm::uvec3> kept;
  for (const glm::uvec3& t : cap.triangles)
    if (cap.positions[t[0]].y < 0.15 || cap.positions[t[1]].y < 0.15 || cap.positions[t[2]].y < 0.15) kept.push_back(t);
  cap.triangles = kept;
  const SdfGrid g = build_sdf(cap, 0.01);
  CHECK_FALSE(g.closed);
  CHECK(g.boundary_edges > 0);
  const MeshColliderT<double> m = identity_collider(g);
  double phi;
  glm::dvec3 grad;
  REQUIRE(sample_mesh_field(m, g.values.data(), glm::dvec3(0.0), phi, grad));
  CHECK(phi == Approx(-g.band));  // the centre is inside, beyond the band
  // Just under the hole's rim plane, on the axis: inside (the hole is closed); above it, outside.
  REQUIRE(sample_mesh_field(m, g.values.data(), glm::dvec3(0, 0.12, 0), phi, grad));
  CHECK(phi < 0);
  REQUIRE(sample_mesh_field(m, g.values.data(), glm::dvec3(0, 0.17, 0), phi, grad));
  CHECK(phi > 0);
  CHECK(winding_number(cap, glm::dvec3(0, 0.17, 0)) < 0.5);
  int checked = 0, wrong = 0;
  for (size_t k = 0; k < g.nodes(); k += 7) {
    const glm::ivec3 at(int(k % size_t(g.dims.x)), int((k / size_t(g.dims.x)) % size_t(g.dims.y)),
                        int(k / (size_t(g.dims.x) * size_t(g.dims.y))));
    const double w = std::abs(winding_number(cap, g.min + glm::dvec3(at) * g.voxel));
    if (std::abs(w - 0.5) < 0.02) continue;  // on the level set itself either sign is right
    ++checked;
    wrong += (g.values[k] < 0) != (w > 0.5);
  }
  INFO(checked << " nodes checked against the exact winding number");
  CHECK(checked > 3000);
  CHECK(wrong == 0);

  // A flat open sheet: its winding number never reaches 1/2, so its field is the unsigned distance.
  SurfaceMesh sheet;
  sheet.positions = {{-0.2, 0, -0.2}, {0.2, 0, -0.2}, {0.2, 0, 0.2}, {-0.2, 0, 0.2}};
  sheet.triangles = {{0, 2, 1}, {0, 3, 2}};
  const SdfGrid f = build_sdf(sheet, 0.01);
  double lowest = 1;
  for (float v : f.values) lowest = std::min(lowest, double(v));
  CHECK(lowest > -1e-9);  // nodes on the sheet itself are 0 either way
}

TEST_CASE("the fast winding number nears the exact sum as its accuracy grows", "[mesh_collider]") {
  // Points in and around an icosphere with a ragged hole (a tenth of its faces gone), near the
  // surface included, where the dipoles of the clusters just past beta radii err the most.
  SurfaceMesh cap = test::icosphere_mesh(0.2, 3);
  cap.triangles.resize(cap.triangles.size() * 9 / 10);
  std::vector<glm::dvec3> points;
  uint32_t seed = 7;
  auto next = [&] { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
  for (int k = 0; k < 2000; ++k) points.emplace_back(0.6 * next() - 0.3, 0.6 * next() - 0.3, 0.6 * next() - 0.3);
  std::vector<double> exact;
  for (const glm::dvec3& p : points) exact.push_back(winding_number(cap, p));
  // Measured: beta 1.5 (the fields') mean 0.012, worst 0.067; 2: 0.0055, 0.027; 3: 0.0020, 0.0105.
  for (auto [beta, mean_limit, worst_limit] : {std::tuple{1.5, 0.015, 0.08}, {2.0, 0.007, 0.035}, {3.0, 0.003, 0.013}}) {
    const FastWindingNumber fast(cap, beta);
    double worst = 0, sum = 0;
    for (size_t k = 0; k < points.size(); ++k) {
      const double e = std::abs(fast(points[k]) - exact[k]);
      worst = std::max(worst, e);
      sum += e;
    }
    INFO("beta " << beta << ": mean |fast - exact| " << sum / double(points.size()) << ", worst " << worst);
    CHECK(sum / double(points.size()) < mean_limit);
    CHECK(worst < worst_limit);
  }
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
    for (const char* solver : {"classic", "fabric"}) {
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
  for (const char* solver : {"classic", "fabric"}) {
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

TEST_CASE("a cloth dropped over the hole of an open mesh stays out of it by the winding number", "[mesh_collider]") {
  // A sphere of 0.2 m with its top cut off above y = 0.1 (a hole 0.35 m across): a 13 x 13 cloth
  // of 0.6 m falls onto it, over the opening. Held out means no mass has an exact winding number
  // above 1/2 (every triangle summed; not the field). An unsigned field, as open meshes had, let
  // the middle of the cloth fall through into the bowl; the field's zero a node off the level
  // set left 8 to 23 masses just inside it.
  test::TempDir dir("mesh_colliders", "open_hole");
  SurfaceMesh bowl = test::icosphere_mesh(0.2, 3);
  std::vector<glm::uvec3> kept;
  for (const glm::uvec3& t : bowl.triangles)
    if (bowl.positions[t[0]].y < 0.1 || bowl.positions[t[1]].y < 0.1 || bowl.positions[t[2]].y < 0.1) kept.push_back(t);
  bowl.triangles = kept;
  const std::string obj = dir / "bowl.obj";
  test::write_obj(bowl, obj);
  for (const char* solver : {"classic", "fabric"}) {
    const Scene s = test::drop_onto_mesh(obj, solver, R"(, "voxel_size": 0.01, "friction": 0.3)", {"cloth.ks=500"});
    const ClothModel model = build_cloth(s);
    CpuBackend<double> run(s, model);
    int worst = 0;
    for (int f = 1; f <= 150; ++f) {
      run.step_frame();
      if (f % 10 != 0) continue;
      int inside = 0;
      for (const auto& p : run.state().pos) {
        const glm::dvec3 local = glm::dvec3(p) - s.meshes[0].origin;
        inside += std::abs(winding_number(bowl, local)) > 0.5;
      }
      worst = std::max(worst, inside);
    }
    // The middle of the cloth, over the middle of the hole, rests on the level set that closes
    // it (0.11 m up there: w = 1/2 exactly at 0.1128), not on the floor of the bowl (-0.2).
    const double middle = run.state().pos[6 * 13 + 6].y - s.meshes[0].origin.y;
    INFO(solver << ": at most " << worst << " masses inside at a tenth frame; the middle rests at y " << middle
                << " m from the centre");
    CHECK(worst == 0);
    CHECK(middle > 0.1);
    CHECK(middle < 0.13);
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
    for (const char* solver : {"classic", "fabric"}) {
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

// The GPU twin of tests/test_mesh_colliders.cpp: a cloth dropped onto each mesh shape gives the
// reference's floats pass by pass and over a whole run (bit for bit on llvmpipe), and never has
// a mass deeper than half a node + 0.1 mm inside the exact shape.
#include <algorithm>
#include <random>

#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "gpu_pass_fixtures.hpp"
#include "colliders/mesh_collider.hpp"
#include "mesh_collider_cases.hpp"
#include "reference/reference_detail.hpp"
#include "sdf_texels.hpp"

TEST_CASE("mesh colliders on the GPU: every pass and a whole drop as the reference, and nothing inside",
          "[gpu][mesh_collider][long]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_mesh_colliders", "drop");
  for (const test::Shape& shape : test::shapes()) {
    const std::string obj = dir / (shape.name + ".obj");
    test::write_obj(shape.mesh, obj);
    // (fabric's sweep decides from predict's clearance bound: mesh_leaves_alone_after.)
    for (const char* solver : {"classic", "fabric"}) {
      INFO(shape.name << ", " << solver);
      // A moving mesh too (the torus rises 5 cm in the first half second), for the motion terms.
      const std::string motion = shape.name == "torus"
                                     ? fmt::format(R"(, "motion": {{"keyframes": [[0, [{0}, {1}, {2}]], [0.5, [{0}, {3}, {2}]]]}})",
                                                   test::kShapeAt.x, test::kShapeAt.y, test::kShapeAt.z,
                                                   test::kShapeAt.y + 0.05)
                                     : "";
      const Scene s = test::drop_onto_mesh(obj, solver, motion);
      const ClothModel model = build_cloth(s);
      pass_fixtures::check_every_pass_alike(s, model, 36);
      GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
      CpuBackend<float> cpu(s, model);
      const double voxel = load_collider_mesh(s, 0)->sdf.voxel;
      double deepest = -1;
      State<float> out;
      for (int f = 0; f < 40; ++f) {
        gpu.step_frame();
        cpu.step_frame();
        gpu.download(out);
        const glm::dvec3 at = glm::dvec3(mesh_origin(cpu.constants().control.meshes[0]));
        for (const auto& p : out.pos) deepest = std::max(deepest, shape.depth(glm::dvec3(p.x, p.y, p.z) - at));
      }
      INFO("deepest inside " << deepest << " m");
      CHECK(deepest <= 0.5 * voxel + 1e-4);
      pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
      pass_fixtures::check_same("displacements", out.disp, cpu.state().disp, pass_fixtures::kRunTolerance);
    }
  }
  CHECK_NO_GL_ERRORS();
}

// Two meshes side by side, their grids overlapping under the cloth: the sweeps' clearance bound
// is the least over the meshes (meshes_leave_alone), and a whole drop onto both is still the
// reference's, bit for bit on llvmpipe.
TEST_CASE("a drop onto two mesh colliders on the GPU is the reference's", "[gpu][mesh_collider][long]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_mesh_colliders", "two");
  const std::vector<test::Shape> shapes = test::shapes();
  const std::string sphere = dir / "icosphere.obj", torus = dir / "torus.obj";
  test::write_obj(shapes[1].mesh, sphere);
  test::write_obj(shapes[2].mesh, torus);
  for (const char* solver : {"classic", "fabric"}) {
    INFO(solver);
    const Scene s = test::make_scene(
        13, 13, 0, {"simulation.self_collision=false", fmt::format("simulation.solver=\"{}\"", solver)},
        fmt::format(R"(, "mesh": [{{"file": "{}", "origin": [0.25, 0.5, 0.5], "friction": 0.3}},
                               {{"file": "{}", "origin": [0.75, 0.45, 0.5], "friction": 0.3}}])",
                    sphere, torus));
    const ClothModel model = build_cloth(s);
    GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
    CpuBackend<float> cpu(s, model);
    REQUIRE(cpu.constants().control.meshes.size() == 2);
    for (int f = 0; f < 40; ++f) {
      gpu.step_frame();
      cpu.step_frame();
    }
    State<float> out;
    gpu.download(out);
    pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
    pass_fixtures::check_same("displacements", out.disp, cpu.state().disp, pass_fixtures::kRunTolerance);
    // Both meshes hold the cloth (in free fall it would be near y 0.05 by now).
    double lowest = 1;
    for (const auto& p : out.pos) lowest = std::min(lowest, double(p.y));
    INFO("lowest mass at y " << lowest);
    CHECK(lowest > 0.35);
  }
  CHECK_NO_GL_ERRORS();
}

// The GPU's texels of the fields (host/gpu/sdf_texels.hpp): texel k is node k and its +x, +y and
// +x+y neighbours, within its own mesh's field (two fields of different shapes side by side), so
// a cell's eight corners are the x, y, z, w of its lower and upper faces' texels.
TEST_CASE("a field's texel holds its node and the node's +x, +y and +x+y neighbours", "[mesh_collider]") {
  std::vector<layout::MeshCollider> meshes(2);
  meshes[0].dims = {3, 4, 2, 0};  // w: the offset
  meshes[1].dims = {5, 2, 3, 24};
  std::vector<float> fields(24 + 30);
  for (size_t k = 0; k < fields.size(); ++k) fields[k] = 0.5f + float(k);
  const std::vector<glm::vec4> texels = sdf_cell_texels(fields, meshes);
  REQUIRE(texels.size() == fields.size());
  for (const layout::MeshCollider& m : meshes)
    for (int z = 0; z < m.dims.z; ++z)
      for (int y = 0; y < m.dims.y; ++y)
        for (int x = 0; x < m.dims.x; ++x) {
          auto node = [&](int i, int j) {
            return i < m.dims.x && j < m.dims.y ? fields[m.dims.w + i + m.dims.x * (j + m.dims.y * z)] : 0.f;
          };
          const glm::vec4 t = texels[m.dims.w + x + m.dims.x * (y + m.dims.y * z)];
          INFO("node " << x << ", " << y << ", " << z << " of the field at " << m.dims.w);
          CHECK(t == glm::vec4(node(x, y), node(x + 1, y), node(x, y + 1), node(x + 1, y + 1)));
        }
}

// The contact list's bound (mesh_leaves_alone_after in compute/collide_meshes.glsl) needs each
// field's slope bound (sdf_slopes) to hold between any two points: checked on the sampled
// fields of the three shapes and of an open box (an unsigned field), 4,000 pairs each, within
// a cell and across the grid; and exactly on a field that is a linear function.
TEST_CASE("a field's slope bound holds between any two points of its grid", "[mesh_collider][long]") {
  test::TempDir dir("gpu_mesh_colliders", "slopes");
  std::vector<test::Shape> shapes = test::shapes();
  test::Shape open_box = shapes[0];
  open_box.name = "open box";
  open_box.mesh.triangles.resize(open_box.mesh.triangles.size() - 2);  // one face gone: not closed
  shapes.push_back(open_box);
  std::mt19937 rng(7);
  for (const test::Shape& shape : shapes) {
    INFO(shape.name);
    const std::string obj = dir / (shape.name + ".obj");
    test::write_obj(shape.mesh, obj);
    const Scene s = test::drop_onto_mesh(obj, "fabric");
    const auto c = make_constants<float>(s, build_cloth(s));
    REQUIRE(c.control.meshes.size() == 1);
    const layout::MeshCollider& m = c.control.meshes[0];
    CHECK((m.material.w == 1.f) == (shape.name != "open box"));  // w: closed
    const float slope = sdf_slopes(*c.sdf, c.control.meshes).at(0);
    INFO("slope bound " << slope);
    // A distance field's neighbours differ by at most a spacing: at most sqrt(3).
    CHECK(slope >= 0.9f);
    CHECK(slope <= 1.7321f);
    const glm::dvec3 extent = glm::dvec3(glm::ivec3(m.dims) - 1) / double(m.grid.w);
    std::uniform_real_distribution<double> unit(0.0, 0.999999);
    double worst = 0;  // the largest |phi(a) - phi(b)| / |a - b| seen
    for (int k = 0; k < 4000; ++k) {
      const glm::dvec3 a = glm::dvec3(unit(rng), unit(rng), unit(rng)) * extent;
      // Every other pair within one node spacing: the slope inside and across a few cells.
      const double reach = k % 2 == 0 ? 1.0 / m.grid.w : glm::length(extent);
      glm::dvec3 b = a + (glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5) * reach;
      b = glm::clamp(b, glm::dvec3(0.0), extent * 0.999999);
      float pa = 0, pb = 0;
      Vec3<float> grad;
      REQUIRE(sample_mesh_field(m, c.sdf->data(), Vec3<float>(m.grid) + Vec3<float>(a), pa, grad));
      REQUIRE(sample_mesh_field(m, c.sdf->data(), Vec3<float>(m.grid) + Vec3<float>(b), pb, grad));
      const double apart = glm::length(b - a);
      if (apart > 1e-4) worst = std::max(worst, std::abs(double(pa) - double(pb)) / apart);
    }
    INFO("steepest sampled " << worst);
    CHECK(worst <= slope * (1 + 1e-3));
    CHECK(worst >= 0.5 * slope);  // and the bound is not loose by much
  }
  // A field of nodes on a plane, phi = 0.3 x - 0.4 y + 1.2 z (m): slope 1.3, exactly as measured.
  std::vector<layout::MeshCollider> plane(1);
  plane[0].dims = {4, 5, 3, 0};
  plane[0].grid.w = 50.f;  // 2 cm
  std::vector<float> nodes;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 4; ++x) nodes.push_back(float((0.3 * x - 0.4 * y + 1.2 * z) * 0.02));
  CHECK(sdf_slopes(nodes, plane).at(0) == Approx(1.3).epsilon(1e-5));
  CHECK(sdf_slopes(nodes, plane).at(0) >= 1.3f * (1 - 1e-6f));
}

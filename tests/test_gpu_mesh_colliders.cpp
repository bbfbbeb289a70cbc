// The GPU twin of tests/test_mesh_colliders.cpp: a cloth dropped onto each mesh shape gives the
// reference's floats pass by pass and over a whole run (bit for bit on llvmpipe), and never has
// a mass deeper than half a node + 0.1 mm inside the exact shape.
#include "backend.hpp"
#include "cloth.hpp"
#include "gpu_pass_fixtures.hpp"
#include "mesh_collider.hpp"
#include "mesh_collider_cases.hpp"
#include "sdf_texels.hpp"

TEST_CASE("mesh colliders on the GPU: every pass and a whole drop as the reference, and nothing inside",
          "[gpu][mesh_collider]") {
  REQUIRE_GL_CONTEXT();
  test::TempDir dir("gpu_mesh_colliders", "drop");
  for (const test::Shape& shape : test::shapes()) {
    const std::string obj = dir / (shape.name + ".obj");
    test::write_obj(shape.mesh, obj);
    for (const char* solver : {"classic", "xpbd"}) {
      INFO(shape.name << ", " << solver);
      // A moving mesh too (the torus rises 5 cm in the first half second), for the motion terms.
      const std::string motion = shape.name == "torus"
                                     ? fmt::format(R"(, "motion": {{"keyframes": [[0, [{0}, {1}, {2}]], [0.5, [{0}, {3}, {2}]]]}})",
                                                   test::kShapeAt.x, test::kShapeAt.y, test::kShapeAt.z,
                                                   test::kShapeAt.y + 0.05)
                                     : "";
      const Scene s = test::drop_onto_mesh(obj, solver, motion);
      const ClothModel model = build_cloth(s);
      {
        GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
        for (const PassError& e : check_passes(s, model, gpu, 36)) {
          INFO(e.pass << ": max |GPU - CPU| = " << e.max_error << " m");
          if (gl::gl_renderer_is_llvmpipe()) CHECK(e.bitwise);
          else CHECK(e.max_error <= pass_fixtures::kPassTolerance);
        }
      }
      GpuSimulator gpu(s, model, pass_fixtures::compute_dir());
      CpuBackend<float> cpu(s, model);
      const double voxel = load_collider_mesh(s, 0)->sdf.voxel;
      double deepest = -1;
      State<float> out;
      for (int f = 0; f < 40; ++f) {
        gpu.step_frame();
        cpu.step_frame();
        gpu.download(out);
        const glm::dvec3 at = glm::dvec3(cpu.constants().meshes[0].origin);
        for (const auto& p : out.pos) deepest = std::max(deepest, shape.depth(glm::dvec3(p.x, p.y, p.z) - at));
      }
      INFO("deepest inside " << deepest << " m");
      CHECK(deepest <= 0.5 * voxel + 1e-4);
      if (gl::gl_renderer_is_llvmpipe()) {
        CHECK(mismatches(out.pos, cpu.state().pos) == 0);
        CHECK(mismatches(out.disp, cpu.state().disp) == 0);
      } else {
        pass_fixtures::check_same("positions", out.pos, cpu.state().pos, pass_fixtures::kRunTolerance);
      }
    }
  }
  CHECK_NO_GL_ERRORS();
}

// The GPU's texels of the fields (host/gpu/sdf_texels.hpp): texel k is node k and its +x, +y and
// +x+y neighbours, within its own mesh's field (two fields of different shapes side by side), so
// a cell's eight corners are the x, y, z, w of its lower and upper faces' texels.
TEST_CASE("a field's texel holds its node and the node's +x, +y and +x+y neighbours", "[mesh_collider]") {
  std::vector<MeshC<float>> meshes(2);
  meshes[0].dims = {3, 4, 2};
  meshes[0].offset = 0;
  meshes[1].dims = {5, 2, 3};
  meshes[1].offset = 24;
  std::vector<float> fields(24 + 30);
  for (size_t k = 0; k < fields.size(); ++k) fields[k] = 0.5f + float(k);
  const std::vector<glm::vec4> texels = sdf_cell_texels(fields, meshes);
  REQUIRE(texels.size() == fields.size());
  for (const MeshC<float>& m : meshes)
    for (int z = 0; z < m.dims.z; ++z)
      for (int y = 0; y < m.dims.y; ++y)
        for (int x = 0; x < m.dims.x; ++x) {
          auto node = [&](int i, int j) {
            return i < m.dims.x && j < m.dims.y ? fields[m.offset + i + m.dims.x * (j + m.dims.y * z)] : 0.f;
          };
          const glm::vec4 t = texels[m.offset + x + m.dims.x * (y + m.dims.y * z)];
          INFO("node " << x << ", " << y << ", " << z << " of the field at " << m.offset);
          CHECK(t == glm::vec4(node(x, y), node(x + 1, y), node(x, y + 1), node(x + 1, y + 1)));
        }
}

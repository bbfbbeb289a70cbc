// `simulate --export-colliders DIR/` (issue 45, item 6): every mesh collider as it stands at
// each exported frame, checked against the file's vertices placed by hand (rotation, origin
// keyed in time), the point cache of them all (mesh.pc2), and the output rules of any export
// (docs/export.md).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "file_support.hpp"
#include "io/point_cache.hpp"
#include "output_support.hpp"
#include "test_helpers.hpp"

using namespace clothsim;
using test::run_binary;
namespace fs = std::filesystem;

namespace {

// A 9x9 cloth falling past the pole of scenes/meshes/pole.obj laid along z (90 degrees about
// x) and lifted 0.2 m over the first 0.2 s; 90 frames/s.
void write_scene(const fs::path& dir) {
  std::ofstream(dir / "s.json") << fmt::format(R"({{
  "cloth": {{"width": 0.3, "height": 0.3, "num_width_points": 9, "num_height_points": 9, "thickness": 0.005,
             "orientation": 0, "pinned": [], "density": 0.15, "ks": 500}},
  "mesh": {{"file": "{}/scenes/meshes/pole.obj", "origin": [0.15, 0.5, 0.15],
            "rotation_axis": [1, 0, 0], "rotation_degrees": 90,
            "motion": {{"keyframes": [[0, [0.15, 0.5, 0.15]], [0.2, [0.15, 0.7, 0.15]]]}}}},
  "simulation": {{"self_collision": false}}
}})",
                                                CLOTHSIM_SOURCE_DIR);
}

}  // namespace

TEST_CASE("simulate --export-colliders writes each mesh collider where it stands at each exported frame", "[export][cli]") {
  test::TempDir dir("collider_export", "frames");
  write_scene(dir.path);
  const std::string scene = (dir.path / "s.json").string(), out = (dir.path / "out/").string();
  REQUIRE(run_binary(fmt::format("simulate '{}' --backend cpu --frames 30 --export-colliders '{}' --export-every 10",
                                 scene, out)) == 0);
  // The file's vertices, rotated by hand: 90 degrees about x takes (x, y, z) to (x, -z, y).
  const std::vector<glm::dvec3> file = test::read_obj_vertices(fs::path(CLOTHSIM_SOURCE_DIR) / "scenes/meshes/pole.obj");
  REQUIRE(file.size() > 10);
  for (int frame : {0, 10, 20, 30}) {
    const fs::path path = dir.path / "out" / "mesh0" / fmt::format("frame_{:04d}.obj", frame);
    INFO(path.string());
    REQUIRE(fs::exists(path));
    const std::vector<glm::dvec3> v = test::read_obj_vertices(path);
    REQUIRE(v.size() == file.size());
    const double t = frame / 90.0;
    const glm::dvec3 origin(0.15, 0.5 + 0.2 * std::min(t / 0.2, 1.0), 0.15);
    double worst = 0;
    for (size_t i = 0; i < v.size(); ++i) {
      const glm::dvec3 expected = glm::dvec3(file[i].x, -file[i].z, file[i].y) + origin;
      worst = std::max(worst, glm::length(v[i] - expected));
    }
    CHECK(worst < 1e-6);
  }
  CHECK_FALSE(fs::exists(dir.path / "out" / "mesh0" / "frame_0005.obj"));
  // And all four as one point cache over frame 0's OBJ: a sample per exported frame, from frame
  // 0, one every 10, each the frame's OBJ rounded to float.
  const std::string cache = (dir.path / "out" / "mesh0" / "mesh.pc2").string();
  const Pc2Header h = read_pc2_header(cache);
  CHECK(h.points == int(file.size()));
  CHECK(h.samples == 4);
  CHECK(h.start_frame == 0.f);
  CHECK(h.sample_rate == 10.f);
  for (int k = 0; k < 4; ++k) {
    const std::vector<glm::dvec3> v =
        test::read_obj_vertices(dir.path / "out" / "mesh0" / fmt::format("frame_{:04d}.obj", 10 * k));
    const std::vector<glm::vec3> sample = read_pc2_sample(cache, k);
    double worst = 0;
    for (size_t i = 0; i < v.size(); ++i) worst = std::max(worst, glm::length(glm::dvec3(sample[i]) - v[i]));
    CHECK(worst < 1e-6);
  }
}

TEST_CASE("simulate --export-colliders follows the rules of every output: exit 2 before the run", "[export][cli]") {
  test::TempDir dir("collider_export", "rules");
  write_scene(dir.path);
  const std::string scene = (dir.path / "s.json").string();
  // The cloth's frames and the collider's in one folder would overwrite each other.
  const std::string same = (dir.path / "same" / "mesh0/").string();
  CHECK(run_binary(fmt::format("simulate '{}' --backend cpu --frames 2 --export '{}' --export-colliders '{}'", scene,
                               same, (dir.path / "same/").string())) == 2);
  CHECK_FALSE(fs::exists(dir.path / "same"));
  // A scene without a mesh collider has nothing to export.
  CHECK(run_binary(fmt::format("simulate '{}/scenes/sphere.json' --backend cpu --frames 1 --export-colliders '{}'",
                               CLOTHSIM_SOURCE_DIR, (dir.path / "none/").string())) == 2);
  CHECK_FALSE(fs::exists(dir.path / "none"));
  // A regular file where a collider's folder would go.
  fs::create_directories(dir.path / "file");
  std::ofstream(dir.path / "file" / "mesh0") << "not a folder";
  CHECK(run_binary(fmt::format("simulate '{}' --backend cpu --frames 1 --export-colliders '{}'", scene,
                               (dir.path / "file/").string())) == 2);
  // --export-every with only the colliders exported is fine.
  CHECK(run_binary(fmt::format("simulate '{}' --backend cpu --frames 2 --export-every 2 --export-colliders '{}'", scene,
                               (dir.path / "every/").string())) == 0);
  CHECK(fs::exists(dir.path / "every" / "mesh0" / "frame_0002.obj"));
}

// Skinned, animated mesh colliders (issue 45, item 1; docs/model.md, "Skinned and animated
// colliders"): a glTF box on one bone (skinned_fixtures.hpp). Linear blend skinning through
// Assimp against the closed form of the bone's motion; the reference's skinning twin against
// the double-precision pose; a cloth that rests on the box rides up with it at the offset the
// field keeps and is carried sideways by friction (and not without it); and the loader's messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "backend.hpp"
#include "colliders/mesh_collider.hpp"
#include "colliders/winding.hpp"
#include "io/point_cache.hpp"
#include "skinned_fixtures.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

constexpr double kThickness = 0.004;

// A 5x5 cloth of 0.1 m at y = 1 over a box of half-size 0.1 whose top is at 0.95, the box's
// bone keyed by `keys` (translations from where it starts).
Scene cloth_on_box(const test::TempDir& dir, const test::BoneKeys& keys, const std::string& solver, double friction,
                   const std::string& extra = "") {
  const std::string file = test::write_skinned_box(dir.path, "box", 0.1f, keys);
  return parse_scene(fmt::format(R"({{
  "cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5, "num_height_points": 5, "thickness": 0.004,
             "orientation": 0, "density": 0.15, "ks": 500, "damping": 0.5}},
  "mesh": {{"file": "{}", "origin": [0.05, 0.85, 0.05], "friction": {}, "thickness": {}, "animation": "move",
            "loop": false{}}},
  "simulation": {{"solver": "{}", "self_collision": false}}
}})",
                                 file, friction, kThickness, extra, solver),
                     dir / "scene.json");
}

// Rises 0.1 m between 0.5 s and 1.5 s (after the cloth has landed), then holds (not looping).
test::BoneKeys rise() { return {{0.f, 0.5f, 1.5f}, {{0, 0, 0}, {0, 0, 0}, {0, 0.1f, 0}}, {}}; }
// Slides 0.05 m along x between 0.5 s and 1.5 s.
test::BoneKeys slide() { return {{0.f, 0.5f, 1.5f}, {{0, 0, 0}, {0, 0, 0}, {0.05f, 0, 0}}, {}}; }

std::string scene_error(const test::TempDir& dir, const std::string& mesh) {
  return test::setup_error(fmt::format(R"({{"cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5,
      "num_height_points": 5, "thickness": 0.004, "orientation": 0}}, "mesh": {}}})", mesh), dir / "bad.json");
}

}  // namespace

TEST_CASE("a skinned box's vertices follow its bone's keys: a quarter turn's half is 45 degrees, slerped",
          "[skinned]") {
  test::TempDir dir("skinned", "turn");
  const glm::quat quarter = glm::angleAxis(float(M_PI / 2), glm::vec3(0, 1, 0));
  const std::string file = test::write_skinned_box(dir.path, "turn", 0.1f, {{0.f, 1.f}, {}, {glm::quat(1, 0, 0, 0), quarter}});
  const Scene s = parse_scene(fmt::format(R"({{"cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5,
      "num_height_points": 5, "thickness": 0.004, "orientation": 0}},
      "mesh": {{"file": "{}", "scale": 2, "origin": [1, 2, 3], "animation": 0}}}})", file), dir / "turn.json");
  // Looping (the default): 1.25 s is 0.25 s into the second turn.
  const auto mesh = load_collider_mesh(s, 0);
  REQUIRE(mesh->skin);
  CHECK(mesh->skin->animation == "move");
  CHECK(mesh->skin->duration_seconds() == Approx(1.0));
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.25}) {
    const std::vector<glm::dvec3> posed = posed_positions(*mesh, s.meshes[0], glm::dvec3(1, 2, 3), t);
    const double a = std::fmod(t, 1.0) * M_PI / 2;  // the bone's angle about y at t (constant speed: slerp)
    for (size_t v = 0; v < posed.size(); ++v) {
      const glm::dvec3 r = mesh->surface.positions[v];  // scaled by 2
      const glm::dvec3 expected(std::cos(a) * r.x + std::sin(a) * r.z + 1, r.y + 2, -std::sin(a) * r.x + std::cos(a) * r.z + 3);
      INFO("t " << t << " vertex " << v);
      CHECK(glm::length(posed[v] - expected) < 1e-6);
    }
  }
}

TEST_CASE("the reference skins each substep as the double-precision pose of the same keys", "[skinned]") {
  test::TempDir dir("skinned", "twin");
  const Scene s = cloth_on_box(dir, rise(), "fabric", 0.5);
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  const auto mesh = load_collider_mesh(s, 0);
  for (int f = 0; f < 100; ++f) {
    cpu.step_frame();
    if (f % 25 != 0) continue;
    // The last substep's end is `time()`: its skinned vertices are where posed_positions puts them.
    const std::vector<glm::dvec3> posed = posed_positions(*mesh, s.meshes[0], s.meshes[0].origin, cpu.time());
    for (size_t v = 0; v < posed.size(); ++v) CHECK(glm::length(glm::dvec3(cpu.constants().control.skinned[v]) - posed[v]) < 1e-12);
  }
}

TEST_CASE("a cloth resting on a skinned box rides up with it and stays its thickness above the top", "[skinned]") {
  test::TempDir dir("skinned", "ride");
  const std::string solver = GENERATE("classic", "fabric");
  const Scene s = cloth_on_box(dir, rise(), solver, 0.5);
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  const auto mesh = load_collider_mesh(s, 0);
  size_t inside = 0;
  for (int f = 1; f <= 270; ++f) {  // 3 s: the box rose from 0.5 s to 1.5 s
    cpu.step_frame();
    if (f % 10 != 0) continue;
    const SurfaceMesh posed{posed_positions(*mesh, s.meshes[0], s.meshes[0].origin, cpu.time()), mesh->surface.triangles};
    for (const auto& p : cpu.state().pos) inside += std::abs(winding_number(posed, glm::dvec3(p))) > 0.5;
  }
  const double top = 0.95 + 0.1;
  double worst = 0;
  for (const auto& p : cpu.state().pos) worst = std::max(worst, std::abs(p.y - (top + kThickness)));
  INFO(solver << ": worst |y - (top + thickness)| = " << worst * 1e3 << " mm");
  CHECK(worst < 5e-4);
  CHECK(inside == 0);
}

TEST_CASE("a skinned box that slides carries the cloth on it by friction, and leaves it without", "[skinned]") {
  test::TempDir dir("skinned", "slide");
  auto carried = [&](double friction) {
    const Scene s = cloth_on_box(dir, slide(), "fabric", friction);
    const ClothModel m = build_cloth(s);
    CpuBackend<double> cpu(s, m);
    for (int f = 0; f < 225; ++f) cpu.step_frame();  // 2.5 s: the slide ended at 1.5 s
    double moved = 0;
    for (size_t i = 0; i < m.initial.size(); ++i) moved += cpu.state().pos[i].x - m.initial[i].x;
    return moved / double(m.initial.size());
  };
  const double sticking = carried(1.0), sliding = carried(0.0);
  INFO("mean x moved: mu = 1 " << sticking * 1e3 << " mm, mu = 0 " << sliding * 1e3 << " mm (the box: 50 mm)");
  CHECK(std::abs(sticking - 0.05) < 0.002);
  CHECK(std::abs(sliding) < 0.002);
}

TEST_CASE("a skinned collider that names no animation of its file is refused with the names it has", "[skinned]") {
  test::TempDir dir("skinned", "errors");
  const std::string box = test::write_skinned_box(dir.path, "box", 0.1f, rise());
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "animation": "run"}})", box)),
             Catch::Contains("mesh.animation") && Catch::Contains("no animation \"run\"") && Catch::Contains("0 \"move\""));
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "animation": 3}})", box)),
             Catch::Contains("mesh.animation") && Catch::Contains("no animation \"3\""));
  const std::string obj = dir / "tri.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n";
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "animation": "walk"}})", obj)),
             Catch::Contains("mesh.animation") && Catch::Contains("has no animations"));
  // A skin without inverseBindMatrices (glTF's default): Assimp 5.2 would crash on it.
  std::ifstream in(box);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string ibm = R"(, "inverseBindMatrices": 6)";
  text.replace(text.find(ibm), ibm.size(), "");
  std::ofstream(dir / "no_ibm.gltf") << text;  // (its buffer is still box.bin)
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "animation": 0}})", dir / "no_ibm.gltf")),
             Catch::Contains("mesh.file") && Catch::Contains("inverseBindMatrices"));
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "animation": 0, "time_scale": -1}})", box)),
             Catch::Contains("mesh.time_scale"));
  CHECK(scene_error(dir, fmt::format(R"({{"file": "{}", "animation": 0, "loop": false}})", box)) == "(no error)");
}

TEST_CASE("a point cache or an OBJ sequence moves a collider's vertices, and a cloth rides up on it", "[skinned]") {
  test::TempDir dir("skinned", "cache");
  // A cube of half-size 0.1 (the glTF box's corners, as OBJ), rising 0.1 m over frames 30 to 120 at 60 frames/s.
  std::string obj = "";
  std::vector<glm::dvec3> corners;
  for (int i = 0; i < 8; ++i) corners.push_back({i & 1 ? 0.1 : -0.1, i & 2 ? 0.1 : -0.1, i & 4 ? 0.1 : -0.1});
  const int tris[] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  auto write_obj = [&](const std::string& path, double lift) {
    std::string text;
    for (const glm::dvec3& c : corners) text += fmt::format("v {} {} {}\n", c.x, c.y + lift, c.z);
    for (int t = 0; t < 36; t += 3) text += fmt::format("f {} {} {}\n", tris[t] + 1, tris[t + 1] + 1, tris[t + 2] + 1);
    std::ofstream(path) << text;
  };
  auto lift_at = [](int frame) { return 0.1 * std::clamp((frame - 30) / 90.0, 0.0, 1.0); };
  write_obj(dir / "cube.obj", 0);
  std::filesystem::create_directories(dir.path / "frames");
  {
    Pc2Writer pc2(dir / "cube.pc2", 8, 0, 1);
    for (int f = 0; f <= 180; ++f) {
      std::vector<glm::dvec4> at;
      for (const glm::dvec3& c : corners) at.push_back({c.x, c.y + lift_at(f), c.z, 1});
      pc2.add(at);
      write_obj(dir / fmt::format("frames/cube_{:04d}.obj", f), lift_at(f));
    }
    pc2.close();
  }
  for (const std::string key : {R"("point_cache": "cube.pc2")", R"("sequence": "frames")"}) {
    INFO(key);
    const Scene s = parse_scene(fmt::format(R"({{
      "cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5, "num_height_points": 5, "thickness": 0.004,
                 "orientation": 0, "density": 0.15, "ks": 500, "damping": 0.5}},
      "mesh": {{"file": "cube.obj", "origin": [0.05, 0.85, 0.05], "friction": 0.5, "thickness": {}, {},
                "cache_frames_per_sec": 60, "loop": false}},
      "simulation": {{"solver": "fabric", "self_collision": false}}
    }})", kThickness, key), dir / "scene.json");
    const auto mesh = load_collider_mesh(s, 0);
    REQUIRE(mesh->skin);
    for (double t : {0.0, 0.75, 1.2, 2.0, 5.0}) {  // frame 45 and 72 are between the ends: linear
      const std::vector<glm::dvec3> posed = posed_positions(*mesh, s.meshes[0], s.meshes[0].origin, t);
      const double lift = 0.1 * std::clamp((t * 60 - 30) / 90.0, 0.0, 1.0);
      for (size_t v = 0; v < 8; ++v) CHECK(glm::length(posed[v] - (corners[v] + glm::dvec3(0.05, 0.85 + lift, 0.05))) < 1e-6);
    }
    const ClothModel m = build_cloth(s);
    CpuBackend<double> cpu(s, m);
    for (int f = 0; f < 270; ++f) cpu.step_frame();
    double worst = 0;
    for (const auto& p : cpu.state().pos) worst = std::max(worst, std::abs(p.y - (1.05 + kThickness)));
    INFO("worst |y - (top + thickness)| = " << worst * 1e3 << " mm");
    CHECK(worst < 5e-4);
  }
  // A cache of another vertex count, and two sources at once, are refused.
  {
    Pc2Writer pc2(dir / "seven.pc2", 7, 0, 1);
    pc2.add(std::vector<glm::dvec4>(7, glm::dvec4(0, 0, 0, 1)));
    pc2.close();
  }
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "point_cache": "{}"}})", dir / "cube.obj", dir / "seven.pc2")),
             Catch::Contains("mesh.point_cache") && Catch::Contains("7 points") && Catch::Contains("8 vertices"));
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "point_cache": "{}", "animation": 0}})", dir / "cube.obj",
                                          dir / "cube.pc2")),
             Catch::Contains("mesh") && Catch::Contains("at most one of animation, point_cache and sequence"));
  CHECK_THAT(scene_error(dir, fmt::format(R"({{"file": "{}", "sequence": "{}"}})", dir / "cube.obj", dir / "cube.obj")),
             Catch::Contains("mesh.sequence") && Catch::Contains("not a folder"));
}

TEST_CASE("a cloth attached to a skinned box follows the vertices it was nearest, m g / k below them",
          "[skinned][attachments]") {
  test::TempDir dir("skinned", "attached");
  const std::string solver = GENERATE("classic", "fabric");
  // The box well below the cloth (its top at 0.6, then 0.7), so that only the attachments act.
  const std::string file = test::write_skinned_box(dir.path, "box", 0.1f, rise());
  const Scene s = parse_scene(fmt::format(R"({{
    "cloth": {{"width": 0.1, "height": 0.1, "num_width_points": 5, "num_height_points": 5, "thickness": 0.004,
               "orientation": 0, "density": 0.15, "ks": 50, "damping": 1,
               "attachments": [{{"collider": "mesh", "box": {{"min": [-1, -1, -1], "max": [1, 2, 1]}}, "stiffness": 10}}]}},
    "mesh": {{"file": "{}", "origin": [0.05, 0.5, 0.05], "friction": 0, "animation": 0, "loop": false}},
    "simulation": {{"solver": "{}", "self_collision": false}}
  }})", file, solver), dir / "scene.json");
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < 450; ++f) cpu.step_frame();  // 5 s: the box rose 0.1 m from 0.5 s to 1.5 s
  const double lag = 0.1 * 0.1 * 0.15 / 25 * 9.8 / 10;  // m g / k
  double worst = 0, sideways = 0;
  for (size_t i = 0; i < m.initial.size(); ++i) {
    const glm::dvec3 x(cpu.state().pos[i]);
    worst = std::max(worst, std::abs((m.initial[i].y + 0.1 - x.y) - lag));
    sideways = std::max({sideways, std::abs(x.x - m.initial[i].x), std::abs(x.z - m.initial[i].z)});
  }
  INFO(solver << ": lag " << lag * 1e3 << " mm; worst deviation " << worst * 1e3 << " mm, sideways " << sideways * 1e3 << " mm");
  CHECK(worst < 0.01 * lag);
  CHECK(sideways < 1e-6);
}

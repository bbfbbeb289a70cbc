// The scene keys of a mesh cloth (cloth.mesh and its placement, pins and mass lumping) and of an
// array of cloths: where the mesh file is looked for, the defaults, grid and mesh keys excluding
// each other, the round trip through scene_to_json and --set on the cloths.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/param_doc.hpp"
#include "scene/scene.hpp"

namespace fs = std::filesystem;
using namespace clothsim;

namespace {

// The SceneError message of `f`, or fails the test when `f` does not throw one.
template <class F>
std::string scene_error(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  FAIL("expected a SceneError, nothing was thrown");
  return {};
}

const char* kGrid = R"({"width": 1, "height": 0.5, "num_width_points": 8, "num_height_points": 6,
                        "thickness": 0.0095, "orientation": 0, "pinned": [[0, 0], [7, 0]]})";
const char* kMesh = R"({"mesh": "meshes/flag.obj", "thickness": 0.002})";

std::string with_cloth(const std::string& cloth) { return R"({"cloth": )" + cloth + "}"; }

// Every member of the two scenes (the structs' operator== is defaulted) but the source.
void require_equal(const Scene& a, const Scene& b) {
  CHECK(a.cloth == b.cloth);
  CHECK(a.extra_cloths == b.extra_cloths);
  CHECK(a.spheres == b.spheres);
  CHECK(a.planes == b.planes);
  CHECK(a.simulation == b.simulation);
  CHECK(a.wind == b.wind);
}

// A scene file in a directory of its own under the system's temporary directory.
struct TempScene {
  fs::path dir, file;
  explicit TempScene(const std::string& text) {
    dir = fs::temp_directory_path() / "clothsim_test_scene_mesh_keys" / "scenes";
    fs::create_directories(dir);
    file = dir / "mesh_scene.json";
    std::ofstream(file) << text;
  }
  ~TempScene() {
    std::error_code ec;
    fs::remove_all(dir.parent_path(), ec);
  }
};

}  // namespace

TEST_CASE("cloth.mesh is found relative to the scene file's directory", "[scene][mesh_keys]") {
  const TempScene t(with_cloth(R"({"mesh": "../meshes/./flag.obj", "thickness": 0.002})"));
  const Scene s = load_scene(t.file);
  CHECK(s.cloth.mesh == "../meshes/./flag.obj");  // as the file writes it
  CHECK(s.cloth.mesh_path == (t.dir.parent_path() / "meshes" / "flag.obj").lexically_normal());
  CHECK(s.cloth.is_mesh());

  // parse_scene's source is the file name.
  CHECK(parse_scene(with_cloth(kMesh), "scenes/x.json").cloth.mesh_path == fs::path("scenes/meshes/flag.obj"));
  CHECK(parse_scene(with_cloth(kMesh), "x.json").cloth.mesh_path == fs::path("meshes/flag.obj"));
  // A scene that is no file: relative to the current directory.
  CHECK(parse_scene(with_cloth(kMesh), "<built-in>").cloth.mesh_path == fs::path("meshes/flag.obj"));
  // An absolute path stays as it is.
  CHECK(parse_scene(with_cloth(R"({"mesh": "/data/flag.obj", "thickness": 0.002})"), "scenes/x.json")
            .cloth.mesh_path == fs::path("/data/flag.obj"));
  // A grid cloth has none.
  CHECK(parse_scene(with_cloth(kGrid), "scenes/x.json").cloth.mesh_path.empty());
}

TEST_CASE("a mesh cloth's keys default, and the grid keys are not required of it", "[scene][mesh_keys]") {
  const Scene s = parse_scene(with_cloth(kMesh), "x.json");
  const ClothParams d;
  CHECK(s.cloth.pinned_vertices.empty());
  CHECK_FALSE(s.cloth.pinned_box.has_value());
  CHECK(s.cloth.scale == 1);
  CHECK(s.cloth.offset == glm::dvec3(0, 0, 0));
  CHECK(s.cloth.rotation_axis == glm::dvec3(0, 1, 0));
  CHECK(s.cloth.rotation_degrees == 0);
  CHECK(s.cloth.mass_lumping == MassLumping::Area);
  CHECK(s.cloth.thickness == 0.002);
  // The grid members keep their defaults.
  CHECK(s.cloth.width == d.width);
  CHECK(s.cloth.num_width_points == d.num_width_points);
  CHECK(s.cloth.pinned.empty());
  CHECK(s.extra_cloths.empty());
  CHECK(s.particle_count() == 0);  // a mesh is counted once loaded

  // The grid cloth: no mesh values.
  const Scene g = parse_scene(with_cloth(kGrid), "x.json");
  CHECK_FALSE(g.cloth.is_mesh());
  CHECK(g.cloth.mesh.empty());
  CHECK(g.particle_count() == 48);
}

TEST_CASE("a mesh cloth's keys load", "[scene][mesh_keys]") {
  const Scene s = parse_scene(with_cloth(R"({"mesh": "m.ply", "thickness": 0.002, "pinned_vertices": [0, 5, 5.0],
      "pinned_box": {"min": [-1, 0.9, -1], "max": [1, 1, 1]}, "scale": 0.01, "offset": [0, 1.5, 0],
      "rotation_axis": [0, 0, -2], "rotation_degrees": -90, "mass_lumping": "uniform", "ks": 300})"),
                              "x.json");
  CHECK(s.cloth.pinned_vertices == std::vector<int>{0, 5, 5});
  REQUIRE(s.cloth.pinned_box.has_value());
  CHECK(s.cloth.pinned_box->min == glm::dvec3(-1, 0.9, -1));
  CHECK(s.cloth.pinned_box->max == glm::dvec3(1, 1, 1));
  CHECK(s.cloth.scale == 0.01);
  CHECK(s.cloth.offset == glm::dvec3(0, 1.5, 0));
  CHECK(s.cloth.rotation_axis == glm::dvec3(0, 0, -1));  // made unit length
  CHECK(s.cloth.rotation_degrees == -90);
  CHECK(s.cloth.mass_lumping == MassLumping::Uniform);
  CHECK(s.cloth.ks == 300);
  // A box may be flat (min == max in a coordinate).
  CHECK_NOTHROW(parse_scene(with_cloth(R"({"mesh": "m.ply", "thickness": 0.002,
      "pinned_box": {"min": [0, 1, 0], "max": [1, 1, 0]}})"), "x.json"));
}

TEST_CASE("grid keys and mesh keys exclude each other, naming both", "[scene][mesh_keys]") {
  auto err = [](const std::string& cloth) { return scene_error([&] { parse_scene(with_cloth(cloth), "t.json"); }); };
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "num_width_points": 8})") ==
        "t.json: cloth.mesh and cloth.num_width_points: a mesh cloth takes its size from the file; remove one of the two");
  // The first grid key in the table's order is named.
  CHECK(err(R"({"num_height_points": 8, "height": 1, "mesh": "m.obj", "thickness": 0.01})") ==
        "t.json: cloth.mesh and cloth.height: a mesh cloth takes its size from the file; remove one of the two");
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "pinned": []})") ==
        "t.json: cloth.mesh and cloth.pinned: a mesh cloth pins with cloth.pinned_vertices or cloth.pinned_box; "
        "remove one of the two");
  const std::string grid = R"({"width": 1, "height": 1, "num_width_points": 8, "num_height_points": 6,
                               "thickness": 0.0095, "orientation": 0, )";
  CHECK(err(grid + R"("pinned_vertices": [0]})") ==
        "t.json: cloth.pinned_vertices is for a mesh cloth (cloth.mesh); a grid cloth pins with cloth.pinned");
  CHECK(err(grid + R"("pinned_box": {"min": [0, 0, 0], "max": [1, 1, 1]}})") ==
        "t.json: cloth.pinned_box is for a mesh cloth (cloth.mesh); a grid cloth pins with cloth.pinned");
  CHECK(err(grid + R"("scale": 2})") ==
        "t.json: cloth.scale is for a mesh cloth (cloth.mesh); a grid cloth's size is cloth.width and cloth.height");
  CHECK(err(grid + R"("rotation_degrees": 2})") ==
        "t.json: cloth.rotation_degrees is for a mesh cloth (cloth.mesh); a grid cloth is placed by cloth.orientation");
  CHECK(err(grid + R"("mass_lumping": "area"})") ==
        "t.json: cloth.mass_lumping is for a mesh cloth (cloth.mesh); a grid cloth's masses are all equal");
  // Both kinds need a thickness; a grid still needs its size.
  CHECK(err(R"({"mesh": "m.obj"})") == "t.json: cloth.thickness: missing required key (expected a number)");
  CHECK(err(R"({"thickness": 0.01})") == "t.json: cloth.width: missing required key (expected a number)");
  // Values of the mesh keys.
  CHECK(err(R"({"mesh": 5, "thickness": 0.01})") == "t.json: cloth.mesh: expected a path to a mesh file, got number 5");
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "pinned_vertices": 3})") ==
        "t.json: cloth.pinned_vertices: expected an array of integers, got number 3");
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "pinned_vertices": [1.5]})") ==
        "t.json: cloth.pinned_vertices[0]: expected an integer, got number 1.5");
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "pinned_box": {"min": [0, 0, 0]}})") ==
        "t.json: cloth.pinned_box.max: missing required key (expected an array of 3 numbers)");
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "scale": -1})") == "t.json: cloth.scale: expected a scale > 0, got -1");
  CHECK(err(R"({"mesh": "m.obj", "thickness": 0.01, "offset": [0, 1]})") ==
        "t.json: cloth.offset: expected an array of 3 numbers, got array [0,1]");
}

TEST_CASE("cloth as an array: the first is Scene::cloth, errors name cloth[i]", "[scene][mesh_keys]") {
  const Scene s = parse_scene(std::string(R"({"cloth": [)") + kGrid + ", " + kMesh + "]}", "scenes/two.json");
  CHECK(s.cloth.num_width_points == 8);
  REQUIRE(s.extra_cloths.size() == 1);
  CHECK(s.extra_cloths[0].mesh_path == fs::path("scenes/meshes/flag.obj"));
  REQUIRE(s.cloths().size() == 2);
  CHECK(s.cloths()[1] == &s.extra_cloths[0]);
  // An array of one is the same scene as the object.
  const Scene one = parse_scene(std::string(R"({"cloth": [)") + kGrid + "]}", "x.json");
  require_equal(one, parse_scene(with_cloth(kGrid), "x.json"));

  auto err = [](const std::string& text) { return scene_error([&] { parse_scene(text, "t.json"); }); };
  CHECK(err(R"({"cloth": []})") == "t.json: cloth: expected at least one cloth object, got an empty array");
  CHECK(err(std::string(R"({"cloth": [)") + kGrid + R"(, {"mesh": "m.obj", "thickness": 0.01, "width": 1}]})") ==
        "t.json: cloth[1].mesh and cloth[1].width: a mesh cloth takes its size from the file; remove one of the two");
  CHECK(err(std::string(R"({"cloth": [)") + kMesh + R"(, {"width": 1, "height": 1, "num_width_points": 8,
        "num_height_points": 6, "thickness": 0.01, "orientation": 0, "scale": 2}]})") ==
        "t.json: cloth[1].scale is for a mesh cloth (cloth[1].mesh); a grid cloth's size is cloth[1].width and "
        "cloth[1].height");
  CHECK(err(std::string(R"({"cloth": [)") + kGrid + R"(, 7]})") == "t.json: cloth[1]: expected an object, got number 7");
  CHECK(err(std::string(R"({"cloth": [)") + kMesh + R"(, {"mesh": "m.obj", "thickness": 0.01,
        "pinned_box": {"min": [0, 0, 1], "max": [0, 0, 0]}}]})") ==
        "t.json: cloth[1].pinned_box: expected min <= max in each of x, y, z, got min [0, 0, 1] and max [0, 0, 0]");
  // The grid cloths together fit in memory like one.
  const std::string big = R"({"width": 1, "height": 1, "num_width_points": 4096, "num_height_points": 3000,
                              "thickness": 0.01, "orientation": 0})";
  CHECK(err(R"({"cloth": [)" + big + ", " + big + "]}") ==
        "t.json: cloth[1].num_width_points: the grid cloths have 24576000 particles in all, too many for memory; at "
        "most 16777216 particles");
  CHECK_THAT(err(R"({"cloth": {}})"), Catch::Contains("t.json: cloth.width: missing required key"));
}

TEST_CASE("two cloths round-trip through scene_to_json to an equal scene", "[scene][mesh_keys]") {
  const Scene s = parse_scene(std::string(R"({"cloth": [)") + kGrid + R"(,
      {"mesh": "../meshes/disc.obj", "thickness": 0.003, "pinned_vertices": [3, 1, 2],
       "pinned_box": {"min": [-0.1, 0.2, -0.3], "max": [0.1, 0.25, 0.3]}, "scale": 0.123456789,
       "offset": [0.1, 2e-7, -3], "rotation_axis": [1, 2, 3], "rotation_degrees": 33.3,
       "mass_lumping": "uniform", "ks": 1234.5678, "damping": 0.5, "enable_bending": false,
       "pinned_motion": {"keyframes": [[0, [0, 0, 0]], [1, [0, 0.5, 0]]]}}],
      "sphere": {"origin": [0, 0, 0], "radius": 0.2, "friction": 0.1},
      "simulation": {"solver": "fabric", "simulation_steps": 20}})",
                              "scenes/two.json");
  const std::string text = scene_to_json(s);
  const nlohmann::json j = nlohmann::json::parse(text);
  REQUIRE(j["cloth"].is_array());
  REQUIRE(j["cloth"].size() == 2);
  // Each cloth is written with the keys of its kind only.
  CHECK(j["cloth"][0].contains("width"));
  CHECK_FALSE(j["cloth"][0].contains("mesh"));
  CHECK_FALSE(j["cloth"][0].contains("scale"));
  CHECK_FALSE(j["cloth"][0].contains("pinned_vertices"));
  CHECK(j["cloth"][1]["mesh"] == "../meshes/disc.obj");  // as the scene wrote it, not mesh_path
  CHECK_FALSE(j["cloth"][1].contains("width"));
  CHECK_FALSE(j["cloth"][1].contains("pinned"));
  CHECK_FALSE(j["cloth"][1].contains("orientation"));
  const Scene back = parse_scene(text, "scenes/two.json");
  require_equal(s, back);
  CHECK(back.extra_cloths.at(0).mesh_path == fs::path("meshes/disc.obj"));
  // And once more: the text is a fixed point.
  CHECK(scene_to_json(back) == text);

  // One cloth is written as the object it always was.
  const Scene one = parse_scene(with_cloth(kMesh), "x.json");
  const nlohmann::json j1 = nlohmann::json::parse(scene_to_json(one));
  REQUIRE(j1["cloth"].is_object());
  CHECK(j1["cloth"] == nlohmann::json::parse(R"({"mesh": "meshes/flag.obj", "thickness": 0.002, "attachments": [], "seams": [], "enable_structural": true,
      "enable_shearing": true, "enable_bending": true, "damping": 0.2, "density": 150.0, "ks": 5000.0,
      "pinned_vertices": [], "scale": 1.0, "offset": [0.0, 0.0, 0.0], "rotation_axis": [0.0, 1.0, 0.0],
      "rotation_degrees": 0.0, "mass_lumping": "area"})"));
  require_equal(one, parse_scene(scene_to_json(one), "x.json"));
  require_equal(default_scene(), parse_scene(scene_to_json(default_scene()), "<built-in pinned2>"));
}

TEST_CASE("overrides edit the first cloth with cloth.KEY, any with cloth[i].KEY, and cloth.mesh makes a grid a mesh",
          "[scene][mesh_keys]") {
  const std::string two = std::string(R"({"cloth": [)") + kGrid + ", " + kMesh + "]}";
  const Scene a = parse_scene(two, "scenes/two.json", {"cloth.ks=77", "cloth[1].ks=88", "cloth[1].scale=0.5"});
  CHECK(a.cloth.ks == 77);
  CHECK(a.extra_cloths.at(0).ks == 88);
  CHECK(a.extra_cloths.at(0).scale == 0.5);
  CHECK(parse_scene(two, "x.json", {"cloth[0].ks=66"}).cloth.ks == 66);
  CHECK(parse_scene(two, "x.json", {"cloth[1].pinned_vertices=[0,5]"}).extra_cloths.at(0).pinned_vertices ==
        std::vector<int>{0, 5});

  // A single cloth object: cloth.KEY and cloth[0].KEY, but no cloth[1].
  const Scene g = parse_scene(with_cloth(kGrid), "x.json", {"cloth[0].ks=55", "cloth.damping=1"});
  CHECK(g.cloth.ks == 55);
  CHECK(g.cloth.damping == 1);
  CHECK_THAT(scene_error([] { parse_scene(with_cloth(kGrid), "x.json", {"cloth[1].ks=1"}); }),
             Catch::Contains("cloth[1].ks") && Catch::Contains("[1] does not name an existing array element"));

  // The mesh keys by --set, the path relative to the scene file.
  const Scene m = parse_scene(with_cloth(kMesh), "scenes/m.json",
                              {"cloth.mesh=\"cloak.obj\"", "cloth.pinned_vertices=[0,5]", "cloth.mass_lumping=uniform",
                               "cloth.pinned_box={\"min\": [0, 0, 0], \"max\": [1, 1, 1]}"});
  CHECK(m.cloth.mesh == "cloak.obj");
  CHECK(m.cloth.mesh_path == fs::path("scenes/cloak.obj"));
  CHECK(m.cloth.pinned_vertices == std::vector<int>{0, 5});
  CHECK(m.cloth.mass_lumping == MassLumping::Uniform);
  CHECK(m.cloth.pinned_box.has_value());
  // A grid cloth (the built-in scene) becomes a mesh cloth: its grid keys go.
  const Scene d = default_scene({"cloth.mesh=tablecloth.obj", "cloth.scale=2"});
  CHECK(d.cloth.mesh_path == fs::path("tablecloth.obj"));
  CHECK(d.cloth.scale == 2);
  CHECK(d.cloth.pinned.empty());
  CHECK(d.cloth.thickness == 0.0095);
  // ...in an array too, and only that cloth's.
  const Scene e = parse_scene(std::string(R"({"cloth": [)") + kGrid + ", " + kGrid + "]}", "x.json",
                              {"cloth[1].mesh=m.obj"});
  CHECK_FALSE(e.cloth.is_mesh());
  CHECK(e.cloth.pinned.size() == 2);
  CHECK(e.extra_cloths.at(0).is_mesh());
  // A grid key set on a mesh cloth is still an error naming both.
  CHECK_THAT(scene_error([] { parse_scene(with_cloth(kMesh), "x.json", {"cloth.width=2"}); }),
             Catch::EndsWith("cloth.mesh and cloth.width: a mesh cloth takes its size from the file; remove one of the "
                             "two"));
  CHECK_THAT(scene_error([] { parse_scene(with_cloth(kMesh), "x.json", {"cloth.pinned_vertices=[-1]"}); }),
             Catch::EndsWith("cloth.pinned_vertices[0]: expected a vertex index >= 0, got -1"));
}

TEST_CASE("the parameter reference documents the mesh keys and the array of cloths", "[scene][mesh_keys]") {
  const std::string md = parameters_markdown();
  for (const char* row : {"| `mesh` | string | absent |", "| `pinned_vertices` | [i, ...] | [] | each ≥ 0 |",
                          "| `pinned_box.min` | [x, y, z] | **required** |", "| `scale` | number | 1 |",
                          "| `mass_lumping` | string | `\"area\"` |", "| `width` | number | **required** (grid cloth) |",
                          "`cloth` is one cloth object, or an array of them"})
    CHECK_THAT(md, Catch::Contains(row));
}

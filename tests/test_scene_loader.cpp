// Scene loading (docs/design.md §4): the classic files load unchanged, the extensions load, and every
// kind of bad input is a SceneError that names the file and the key path.
#include <catch2/catch.hpp>

#include "bad_scenes.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace fs = std::filesystem;
using namespace clothsim;

namespace {

const fs::path kSource = CLOTHSIM_SOURCE_DIR;
const fs::path kBad = test::kBadScenes;


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

const char* kCloth = R"("cloth": {"width": 1, "height": 1, "num_width_points": 8, "num_height_points": 6,
                                  "thickness": 0.0095, "orientation": 0})";

Scene parse_with(const std::string& extra, const std::vector<std::string>& sets = {}) {
  return parse_scene(std::string("{") + kCloth + extra + "}", "test.json", sets);
}

std::string fmt_plane(double x, double y, double z) {
  std::ostringstream o;
  o.precision(17);
  o << R"(, "plane": {"point": [0, 0, 0], "friction": 0, "normal": [)" << x << ", " << y << ", " << z << "]}";
  return o.str();
}

void require_same(const Scene& a, const Scene& b) {
  CHECK((a.cloth.width == b.cloth.width && a.cloth.height == b.cloth.height));
  CHECK((a.cloth.num_width_points == b.cloth.num_width_points && a.cloth.num_height_points == b.cloth.num_height_points));
  CHECK(a.cloth.thickness == b.cloth.thickness);
  CHECK(a.cloth.orientation == b.cloth.orientation);
  CHECK(a.cloth.pinned == b.cloth.pinned);
  CHECK((a.cloth.enable_structural == b.cloth.enable_structural && a.cloth.enable_shearing == b.cloth.enable_shearing &&
         a.cloth.enable_bending == b.cloth.enable_bending));
  CHECK(a.cloth.damping == b.cloth.damping);
  CHECK(a.cloth.density == b.cloth.density);
  CHECK(a.cloth.ks == b.cloth.ks);
  REQUIRE(a.spheres.size() == b.spheres.size());
  for (size_t i = 0; i < a.spheres.size(); ++i) {
    CHECK(a.spheres[i].origin == b.spheres[i].origin);
    CHECK(a.spheres[i].radius == b.spheres[i].radius);
    CHECK(a.spheres[i].friction == b.spheres[i].friction);
  }
  REQUIRE(a.planes.size() == b.planes.size());
  for (size_t i = 0; i < a.planes.size(); ++i) {
    CHECK(a.planes[i].point == b.planes[i].point);
    CHECK(a.planes[i].normal == b.planes[i].normal);
    CHECK(a.planes[i].friction == b.planes[i].friction);
  }
  CHECK(a.simulation.frames_per_sec == b.simulation.frames_per_sec);
  CHECK(a.simulation.simulation_steps == b.simulation.simulation_steps);
  CHECK(a.simulation.gravity == b.simulation.gravity);
  CHECK(a.simulation.max_stretch == b.simulation.max_stretch);
  CHECK(a.simulation.constraint_iterations == b.simulation.constraint_iterations);
  CHECK(a.simulation.self_collision == b.simulation.self_collision);
}

}  // namespace

TEST_CASE("every malformed scene in the corpus is rejected naming the file and the key", "[scene]") {
  const auto manifest = test::read_bad_scene_manifest();
  REQUIRE(manifest.size() >= 40);
  for (const auto& [file, expected] : manifest) {
    INFO(file);
    const fs::path path = kBad / file;
    REQUIRE(fs::exists(path));
    const std::string msg = scene_error([&] { load_scene(path); });
    CHECK_THAT(msg, Catch::Contains(path.string()));
    CHECK_THAT(msg, Catch::Contains(expected));
  }
}

TEST_CASE("the bad-scene manifest lists every file of the corpus", "[scene]") {
  std::set<std::string> listed;
  for (const auto& entry : test::read_bad_scene_manifest()) CHECK(listed.insert(entry.first).second);
  for (const auto& entry : fs::directory_iterator(kBad)) {
    if (entry.path().extension() != ".json") continue;
    INFO(entry.path().filename().string());
    CHECK(listed.count(entry.path().filename().string()) == 1);
  }
}

TEST_CASE("a missing scene file is an error naming the file", "[scene]") {
  const fs::path missing = kBad / "no_such_scene.json";
  CHECK_THAT(scene_error([&] { load_scene(missing); }), Catch::Contains(missing.string()));
}

TEST_CASE("the five classic scenes load with the classic values", "[scene]") {
  for (const char* name : {"pinned2", "pinned4", "sphere", "plane", "selfCollision"}) {
    INFO(name);
    const Scene s = load_scene(kSource / "scenes" / (std::string(name) + ".json"));
    CHECK(s.name() == name);
    CHECK(s.cloth.width == 1.0);
    CHECK(s.cloth.height == 1.0);
    CHECK(s.cloth.num_width_points == 50);
    CHECK(s.cloth.num_height_points == 50);
    CHECK(s.cloth.ks == 5000);
    CHECK(s.cloth.density == 150);
    CHECK(s.cloth.damping == 0.2);
    CHECK(s.cloth.thickness == 0.0095);
    CHECK((s.cloth.enable_structural && s.cloth.enable_shearing && s.cloth.enable_bending));
    CHECK(s.simulation.frames_per_sec == 90);
    CHECK(s.simulation.simulation_steps == 30);
    CHECK(s.simulation.gravity == glm::dvec3(0, -9.8, 0));
  }
  using Pins = std::vector<std::array<int, 2>>;
  const Scene p2 = load_scene(kSource / "scenes/pinned2.json");
  CHECK(p2.cloth.orientation == Orientation::Horizontal);
  CHECK(p2.cloth.pinned == Pins{{0, 0}, {49, 0}});
  CHECK(p2.spheres.empty());
  CHECK(p2.planes.empty());
  CHECK(load_scene(kSource / "scenes/pinned4.json").cloth.pinned == Pins{{0, 0}, {49, 0}, {0, 49}, {49, 49}});

  const Scene sp = load_scene(kSource / "scenes/sphere.json");
  REQUIRE(sp.spheres.size() == 1);
  CHECK(sp.spheres[0].origin == glm::dvec3(0.5, 0.2, 0.5));
  CHECK(sp.spheres[0].radius == 0.2);
  CHECK(sp.spheres[0].friction == 0.3);
  CHECK(sp.planes.empty());

  for (const char* name : {"plane", "selfCollision"}) {
    INFO(name);
    const Scene pl = load_scene(kSource / "scenes" / (std::string(name) + ".json"));
    REQUIRE(pl.planes.size() == 1);
    CHECK(pl.planes[0].point == glm::dvec3(0, 0, 0));
    CHECK(pl.planes[0].normal == glm::dvec3(0, 1, 0));
    CHECK(pl.planes[0].friction == 0.5);
    CHECK(pl.cloth.pinned.empty());
  }
  CHECK(load_scene(kSource / "scenes/plane.json").cloth.orientation == Orientation::Horizontal);
  CHECK(load_scene(kSource / "scenes/selfCollision.json").cloth.orientation == Orientation::Vertical);
}

TEST_CASE("integer and float spellings of a number are both accepted", "[scene]") {
  CHECK(parse_with("", {"cloth.width=1"}).cloth.width == 1.0);
  CHECK(parse_with("", {"cloth.width=1.0"}).cloth.width == 1.0);
  CHECK(parse_with("", {"cloth.width=2.5e0"}).cloth.width == 2.5);
  CHECK(parse_with("", {"cloth.num_width_points=50.0"}).cloth.num_width_points == 50);
  CHECK_THAT(scene_error([] { parse_with("", {"cloth.num_width_points=50.5"}); }),
             Catch::Contains("cloth.num_width_points: expected an integer"));
}

TEST_CASE("colliders given as arrays load in file order", "[scene]") {
  const Scene s = parse_with(R"(,
    "sphere": [{"origin": [0, 0, 0], "radius": 0.1, "friction": 0.1},
               {"origin": [1, 2, 3], "radius": 0.2, "friction": 0.2},
               {"origin": [4, 5, 6], "radius": 0.3, "friction": 0.3}],
    "plane": [{"point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5},
              {"point": [0, 1, 0], "normal": [1, 0, 0], "friction": 0}])");
  REQUIRE(s.spheres.size() == 3);
  for (int i = 0; i < 3; ++i) {
    CHECK(s.spheres[i].radius == Approx(0.1 * (i + 1)));
    CHECK(s.spheres[i].friction == Approx(0.1 * (i + 1)));
  }
  CHECK(s.spheres[2].origin == glm::dvec3(4, 5, 6));
  REQUIRE(s.planes.size() == 2);
  CHECK(s.planes[0].normal == glm::dvec3(0, 1, 0));
  CHECK(s.planes[1].point == glm::dvec3(0, 1, 0));
  CHECK(s.planes[1].normal == glm::dvec3(1, 0, 0));
  CHECK(parse_with(R"(, "sphere": [], "plane": [])").spheres.empty());
}

TEST_CASE("a plane normal is normalised and may point either way", "[scene]") {
  const Scene s = parse_with(R"(, "plane": {"point": [0, 0, 0], "normal": [0, -2, 0], "friction": 0})");
  CHECK(s.planes.at(0).normal == glm::dvec3(0, -1, 0));
  const Scene big = parse_with(R"(, "plane": {"point": [0, 0, 0], "normal": [0, 0, 1e300], "friction": 0})");
  CHECK(big.planes.at(0).normal == glm::dvec3(0, 0, 1));
  const glm::dvec3 n = parse_with(R"(, "plane": {"point": [0, 0, 0], "normal": [1, 2, 3], "friction": 0})")
                           .planes.at(0).normal;
  CHECK(n.x * n.x + n.y * n.y + n.z * n.z == Approx(1.0).epsilon(1e-15));
  CHECK(n.y == Approx(2 * n.x));
  CHECK(n.z == Approx(3 * n.x));
}

TEST_CASE("the simulation block loads its values", "[scene]") {
  const Scene s = parse_with(R"(, "simulation": {"frames_per_sec": 60, "simulation_steps": 45,
      "gravity": [1, -3.5, 0.25], "max_stretch": 0.05, "constraint_iterations": 4, "self_collision": false})");
  CHECK(s.simulation.frames_per_sec == 60);
  CHECK(s.simulation.simulation_steps == 45);
  CHECK(s.simulation.gravity == glm::dvec3(1, -3.5, 0.25));
  CHECK(s.simulation.max_stretch == 0.05);
  CHECK(s.simulation.constraint_iterations == 4);
  CHECK_FALSE(s.simulation.self_collision);
  CHECK(s.dt() == Approx(1.0 / 60 / 45));
  // Without the block: the defaults of docs/design.md §1.
  const Scene d = parse_with("");
  CHECK(d.simulation.frames_per_sec == 90);
  CHECK(d.simulation.simulation_steps == 30);
  CHECK(d.simulation.max_stretch == 0.1);
  CHECK(d.simulation.constraint_iterations == 1);
  CHECK(d.simulation.self_collision);
}

TEST_CASE("overrides given with --set replace and create scene values", "[scene]") {
  const Scene s = load_scene(kSource / "scenes/pinned2.json",
                             {"cloth.ks=500", "simulation.gravity=[0,0,0]", "simulation.self_collision=false",
                              "cloth.pinned=[[1,1]]", "cloth.orientation=1"});
  CHECK(s.cloth.ks == 500);
  CHECK(s.simulation.gravity == glm::dvec3(0, 0, 0));
  CHECK_FALSE(s.simulation.self_collision);  // the file has no simulation block: it is created
  CHECK(s.simulation.simulation_steps == 30);
  CHECK(s.cloth.pinned == std::vector<std::array<int, 2>>{{1, 1}});
  CHECK(s.cloth.orientation == Orientation::Vertical);

  const char* two_spheres = R"(, "sphere": [{"origin": [0, 0, 0], "radius": 0.1, "friction": 0.1},
                                            {"origin": [1, 1, 1], "radius": 0.2, "friction": 0.2}])";
  const Scene arr = parse_with(two_spheres, {"sphere[0].radius=0.3", "sphere[1].origin[2]=5"});
  CHECK(arr.spheres.at(0).radius == 0.3);
  CHECK(arr.spheres.at(1).radius == 0.2);
  CHECK(arr.spheres.at(1).origin == glm::dvec3(1, 1, 5));

  const Scene obj = load_scene(kSource / "scenes/sphere.json", {"sphere.radius=0.3"});
  CHECK(obj.spheres.at(0).radius == 0.3);
  CHECK(obj.spheres.at(0).origin == glm::dvec3(0.5, 0.2, 0.5));

  CHECK(default_scene({"cloth.ks=10"}).cloth.ks == 10);
  CHECK(default_scene().cloth.pinned.size() == 2);
}

TEST_CASE("a bad --set override is a SceneError naming the key", "[scene]") {
  auto err = [](std::vector<std::string> sets) {
    return scene_error([&] { load_scene(kSource / "scenes/sphere.json", sets); });
  };
  CHECK_THAT(err({"cloth.ks"}), Catch::Contains("cloth.ks") && Catch::Contains("key.path=value"));
  CHECK_THAT(err({"=5"}), Catch::Contains("key.path=value"));
  CHECK_THAT(err({"cloth.stiffness=5"}), Catch::Contains("cloth.stiffness: unknown key"));
  CHECK_THAT(err({"cloth.ks=abc"}), Catch::Contains("cloth.ks: expected a number, got string"));
  CHECK_THAT(err({"cloth.enable_bending=1"}), Catch::Contains("cloth.enable_bending: expected true or false"));
  CHECK_THAT(err({"sphere[0].radius=0.3"}), Catch::Contains("sphere[0].radius"));  // sphere is an object here
  const char* two = R"(, "sphere": [{"origin": [0, 0, 0], "radius": 0.1, "friction": 0.1},
                                    {"origin": [1, 1, 1], "radius": 0.2, "friction": 0.2}])";
  CHECK_THAT(scene_error([&] { parse_with(two, {"sphere[2].radius=0.3"}); }),
             Catch::Contains("sphere[2].radius") && Catch::Contains("existing array element"));
  CHECK_THAT(scene_error([&] { parse_with(two, {"sphere.radius=0.3"}); }), Catch::Contains("sphere.radius"));
  CHECK_THAT(err({"cloth.width.x=1"}), Catch::Contains("cloth.width.x") && Catch::Contains("not an object"));
  CHECK_THAT(err({"cloth..ks=1"}), Catch::Contains("cloth..ks"));
  CHECK_THAT(err({"cloth.=1"}), Catch::Contains("empty key"));
  CHECK_THAT(err({"sphere[x].radius=1"}), Catch::Contains("sphere[x].radius"));
  CHECK_THAT(err({"sphere.radius=-1"}), Catch::Contains("sphere.radius: expected a radius > 0"));
  // Overrides name the scene file too.
  CHECK_THAT(err({"cloth.ks=abc"}), Catch::Contains("sphere.json"));
  // Overrides apply before validation: a --set can also repair a value.
  CHECK(load_scene(kBad / "negative_width.json", {"cloth.width=2"}).cloth.width == 2);
}

TEST_CASE("a message shows only the start of a long value or override and never half a character", "[scene]") {
  const std::string value = scene_error([] { parse_with("", {"cloth.ks=" + std::string(1000, 'x')}); });
  CHECK_THAT(value, Catch::EndsWith("cloth.ks: expected a number, got string \"" + std::string(36, 'x') + "..."));
  const std::string override = scene_error([] { parse_with("", {"cloth.width.a=" + std::string(1000, 'x')}); });
  CHECK_THAT(override, Catch::Contains("--set cloth.width.a=" + std::string(63, 'x') + "...: 'a' is inside"));
  std::string accents;
  for (int i = 0; i < 40; ++i) accents += "\xc3\xa9";  // "é" is two bytes: cutting "\"aéé..." at 37 bytes would split one
  const std::string utf8 = scene_error([&] { parse_with("", {"cloth.ks=a" + accents}); });
  CHECK_THAT(utf8, Catch::EndsWith("got string \"a" + accents.substr(0, 34) + "..."));
  CHECK_THAT(scene_error([] { load_scene(kBad / "ks_null.json"); }), Catch::EndsWith("expected a number, got null"));
}

TEST_CASE("scene_to_json round-trips to an equal scene", "[scene]") {
  Scene s = parse_with(R"(,
    "sphere": [{"origin": [0.1, 0.2, 0.3], "radius": 0.123456789, "friction": 0.3},
               {"origin": [-1, 2e-7, 3], "radius": 1e-3, "friction": 1}],
    "plane": [{"point": [0, 0.1, 0], "normal": [1, 2, 3], "friction": 0.7},
              {"point": [0, 0, 0], "normal": [0, -1, 0], "friction": 0}],
    "simulation": {"frames_per_sec": 59.94, "simulation_steps": 17, "gravity": [0.1, -9.81, 1e-9],
                   "max_stretch": 0.0333, "constraint_iterations": 3, "self_collision": false})",
                       {"cloth.pinned=[[0,0],[7,5],[3,2]]", "cloth.damping=0.123", "cloth.density=0.1",
                        "cloth.ks=1234.5678", "cloth.enable_shearing=false", "cloth.orientation=1",
                        "cloth.thickness=0.001", "cloth.width=1.7", "cloth.height=0.3"});
  const Scene back = parse_scene(scene_to_json(s), "round-trip.json");
  require_same(s, back);
  require_same(load_scene(kSource / "scenes/selfCollision.json"),
               parse_scene(scene_to_json(load_scene(kSource / "scenes/selfCollision.json")), "x.json"));
  require_same(default_scene(), parse_scene(scene_to_json(default_scene()), "x.json"));
  // Normalising a normal is idempotent, so a saved normal loads back bit for bit.
  for (double x = -1; x <= 1; x += 0.25)
    for (double z = -1; z <= 1; z += 0.125) {
      const Scene p = parse_with(fmt_plane(x, 0.3, z));
      CHECK(parse_scene(scene_to_json(p), "x.json").planes.at(0).normal == p.planes.at(0).normal);
    }
}

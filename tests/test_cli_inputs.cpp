// Hostile inputs at the command line (issue 41): empty paths, FIFOs and devices, symlink loops,
// NaN in options, control characters in names read from files, out of memory, a fully pinned
// static solve. Each runs the built binary; a run that would block is cut by `timeout`.
#include <catch2/catch.hpp>

#include "cli_support.hpp"

#include <sys/stat.h>

#include <string>
#include <vector>

using namespace clothsim::test;

namespace {

const std::string kPinned2 = (kSource / "scenes/pinned2.json").string();
// A run that blocked on a FIFO before the fix ends here with 124 instead of hanging the suite.
const char* kTimeout = "timeout 30";

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// A small odd grid, pinned at two corners, with `extra` keys in the cloth object.
std::string grid_scene(const std::string& extra = "", const std::string& top = "") {
  return R"({"cloth": {"width": 1, "height": 1, "num_width_points": 5, "num_height_points": 7, "thickness": 0.01,
             "orientation": 0, "pinned": [[0, 6], [4, 6]])" + extra + "}" + top + "}";
}

void check_refused(const Result& r, const std::string& name, const std::string& why) {
  INFO("stderr: " << r.err);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(name));
  CHECK_THAT(r.err, Catch::Contains(why));
}

}  // namespace

TEST_CASE("an empty path as the scene or the state is exit 2, not the built-in scene", "[cli][inputs]") {
  const Result scene = run({"simulate", "", "--frames", "1", "--backend", "cpu"});
  check_refused(scene, "\"\"", "an empty path");
  const Result state = run({"simulate", kPinned2, "--frames", "1", "--backend", "cpu", "--load-state", ""});
  check_refused(state, "--load-state", "an empty path");
}

TEST_CASE("a FIFO, a device or a directory as scene, mesh or state is exit 2 at once", "[cli][inputs]") {
  TempFile dir("fifos");
  fs::create_directories(dir.path);
  const fs::path fifo = dir.path / "scene.json";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  check_refused(run({"simulate", fifo.string(), "--frames", "1", "--backend", "cpu"}, kTimeout), fifo.string(),
                "is a FIFO (named pipe), not a regular file");
  check_refused(run({"simulate", "/dev/zero", "--frames", "1", "--backend", "cpu"}, kTimeout), "/dev/zero",
                "is a character device");
  check_refused(run({"simulate", dir.path.string(), "--frames", "1", "--backend", "cpu"}, kTimeout),
                dir.path.string(), "is a directory");

  // A mesh cloth and a mesh collider whose file is a FIFO (Assimp blocked on it).
  const fs::path mesh_fifo = dir.path / "cloth.obj";
  REQUIRE(mkfifo(mesh_fifo.c_str(), 0600) == 0);
  write(dir.path / "mesh_cloth.json", R"({"cloth": {"mesh": "cloth.obj", "thickness": 0.01}})");
  check_refused(run({"simulate", (dir.path / "mesh_cloth.json").string(), "--frames", "1", "--backend", "cpu"},
                    kTimeout),
                "cloth.obj", "is a FIFO");
  write(dir.path / "collider.json", grid_scene("", R"(, "mesh": {"file": "cloth.obj"})"));
  check_refused(run({"simulate", (dir.path / "collider.json").string(), "--frames", "1", "--backend", "cpu"},
                    kTimeout),
                "mesh.file", "is a FIFO");

  const fs::path state_fifo = dir.path / "run.state";
  REQUIRE(mkfifo(state_fifo.c_str(), 0600) == 0);
  check_refused(run({"simulate", kPinned2, "--frames", "1", "--backend", "cpu", "--load-state",
                     state_fifo.string()},
                    kTimeout),
                state_fifo.string(), "is a FIFO");
}

TEST_CASE("a symlink loop and a name too long say so in words", "[cli][inputs]") {
  TempFile dir("links");
  fs::create_directories(dir.path);
  fs::create_symlink(dir.path / "b.json", dir.path / "a.json");
  fs::create_symlink(dir.path / "a.json", dir.path / "b.json");
  check_refused(run({"simulate", (dir.path / "a.json").string(), "--frames", "1", "--backend", "cpu"}),
                (dir.path / "a.json").string(), "a loop of symbolic links (ELOOP");
  const std::string long_name = (dir.path / (std::string(300, 'n') + ".json")).string();
  check_refused(run({"simulate", long_name, "--frames", "1", "--backend", "cpu"}), long_name,
                "the name is too long (ENAMETOOLONG)");
}

TEST_CASE("NaN and infinity are refused by name in numeric options", "[cli][inputs]") {
  // Each is refused while the command line is read, before any GL context or scene.
  const std::vector<std::vector<std::string>> cases = {
      {"render", kPinned2, "--frames", "1", "--out", "x.png", "--camera", "nan,0,0,0,0,0"},
      {"render", kPinned2, "--frames", "1", "--out", "x.png", "--exposure", "nan"},
      {"render", kPinned2, "--frames", "1", "--out", "x.png", "--light", "1,inf,0"},
      {"validate", kPinned2, "--frames", "1", "--tolerance", "nan"},
      {"static", kPinned2, "--tolerance", "inf"},
      {"bench", "--cpu-limit", "-inf"},
  };
  for (const auto& args : cases) {
    const Result r = run(args);
    INFO(args[0] << " " << args[args.size() - 2] << " " << args.back() << "\n" << r.both());
    CHECK(r.code == 2);
    CHECK_THAT(r.both(), Catch::Contains(args[args.size() - 2]));
    const bool named = r.both().find("NaN is not a number here") != std::string::npos ||
                       r.both().find("infinity is not accepted") != std::string::npos;
    CHECK(named);
  }
}

TEST_CASE("option ranges are printed readably, not as DBL_MAX's 309 digits", "[cli][inputs]") {
  const Result r = run({"static", kPinned2, "--tolerance", "-1"});
  INFO(r.both());
  CHECK(r.code == 2);
  CHECK_THAT(r.both(), Catch::Contains("--tolerance"));
  CHECK_THAT(r.both(), Catch::Contains("expected a number > 0, got -1"));
  CHECK(r.both().find("179769313486231") == std::string::npos);
  const Result help = run({"render", "--help"});
  CHECK(help.both().find("179769313486231") == std::string::npos);
  CHECK_THAT(help.both(), Catch::Contains("a number in [0.01, 100]"));
}

TEST_CASE("control characters in names read from files are escaped when printed", "[cli][inputs]") {
  TempFile dir("escapes");
  fs::create_directories(dir.path);
  // A state records its scene's name; a scene file named with an escape sequence saves one.
  const fs::path evil = dir.path / "evil\x1b[2J\x1b[31m.json";
  write(evil, grid_scene());
  const fs::path state = dir.path / "run.state";
  REQUIRE(run({"simulate", evil.string(), "--frames", "1", "--backend", "cpu", "--save-state", state.string()}).code ==
          0);
  write(dir.path / "plain.json", grid_scene());
  const Result r = run({"simulate", (dir.path / "plain.json").string(), "--frames", "1", "--backend", "cpu",
                        "--load-state", state.string()});
  INFO(r.both());
  CHECK(r.code == 0);
  CHECK(r.both().find('\x1b') == std::string::npos);
  CHECK_THAT(r.out, Catch::Contains("evil\\x1b[2J\\x1b[31m.json"));

  // A key read from a scene file, named in the error.
  write(dir.path / "key.json", grid_scene("", R"(, "colour\u001b]0;owned\u0007": 1)"));
  const Result key = run({"simulate", (dir.path / "key.json").string(), "--frames", "1", "--backend", "cpu"});
  INFO(key.err);
  CHECK(key.code == 2);
  CHECK(key.err.find('\x1b') == std::string::npos);
  CHECK(key.err.find('\x07') == std::string::npos);
  CHECK_THAT(key.err, Catch::Contains("colour\\x1b]0;owned\\x07: unknown key"));
}

TEST_CASE("out of host memory is exit 2 naming what was allocated and its size", "[cli][inputs]") {
  // Under ASan no address-space limit can be set, and its operator new aborts instead of
  // throwing: the normal build runs this test.
  if (kAddressSanitizer) return;
  // The largest grid accepted, in 700 MB of address space: its model cannot be allocated.
  const Result r = run({"simulate", kPinned2, "--frames", "1", "--backend", "cpu", "--set",
                        "cloth.num_width_points=4095", "--set", "cloth.num_height_points=4095", "--set",
                        "cloth.pinned=[[0,0]]"},
                       address_space_limit("700000"));
  INFO(r.both());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("out of host memory allocating the cloth model of 16769025 particles"));
  CHECK_THAT(r.err, Catch::Contains("MiB"));
}

TEST_CASE("static refuses a scene with a mesh collider as it does spheres and planes: exit 2", "[cli][inputs]") {
  TempFile dir("static_mesh");
  fs::create_directories(dir.path);
  write(dir.path / "mesh.json",
        R"({"cloth": {"width": 1, "height": 1, "num_width_points": 3, "num_height_points": 3, "thickness": 0.01,
            "orientation": 0, "pinned": [[0, 0]]},
            "mesh": {"file": ")" + (kSource / "scenes/meshes/pole.obj").string() + R"(", "origin": [0, 0, 0]},
            "simulation": {"self_collision": false}})");
  const Result r = run({"static", (dir.path / "mesh.json").string()});
  INFO(r.both());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("no colliders"));
}

TEST_CASE("static refuses a cloth with a material (its membrane is the fabric sweep's): exit 2", "[cli][inputs]") {
  TempFile dir("static_material");
  fs::create_directories(dir.path);
  write(dir.path / "silk.json",
        R"({"cloth": {"width": 1, "height": 1, "num_width_points": 3, "num_height_points": 3, "thickness": 0.01,
            "orientation": 0, "pinned": [[0, 0]], "material": "silk"},
            "simulation": {"solver": "fabric", "self_collision": false}})");
  const Result r = run({"static", (dir.path / "silk.json").string()});
  INFO(r.both());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("silk.json"));
  CHECK_THAT(r.err, Catch::Contains("cloth.material"));
}

TEST_CASE("static on a cloth whose every particle is pinned says so and exits 0", "[cli][inputs]") {
  TempFile dir("pinned");
  fs::create_directories(dir.path);
  std::string pins;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y) pins += (pins.empty() ? "" : ", ") + ("[" + std::to_string(x) + ", " + std::to_string(y) + "]");
  write(dir.path / "all_pinned.json",
        R"({"cloth": {"width": 1, "height": 1, "num_width_points": 3, "num_height_points": 3, "thickness": 0.01,
            "orientation": 0, "pinned": [)" + pins + "]}, \"simulation\": {\"self_collision\": false}}");
  const fs::path obj = dir.path / "rest.obj";
  const Result r = run({"static", (dir.path / "all_pinned.json").string(), "--export", obj.string()});
  INFO(r.both());
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("nothing to solve: every particle is pinned"));
  CHECK(fs::exists(obj));
}

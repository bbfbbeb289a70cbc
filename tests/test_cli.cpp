// The command line as a user meets it (docs/design.md §3): runs the built `clothsim` binary and checks
// exit codes, messages and the OBJ export.
#include <catch2/catch.hpp>

#include "cli_support.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

using namespace clothsim::test;

TEST_CASE("the clothsim binary has been built", "[cli]") { REQUIRE(fs::exists(kBinary)); }

TEST_CASE("every malformed scene exits 2 naming the file and the key", "[cli]") {
  const auto manifest = clothsim::test::read_bad_scene_manifest();
  REQUIRE(manifest.size() >= 40);
  for (const auto& [file, expected] : manifest) {
    const std::string path = (kBad / file).string();
    const Result r = run({"simulate", path, "--frames", "1", "--backend", "cpu"});
    INFO(file << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains(path));
    CHECK_THAT(r.err, Catch::Contains(expected));
  }
}

TEST_CASE("every bad mesh cloth exits 2 naming the scene, the mesh file and what is wrong", "[cli][mesh]") {
  const fs::path dir = fs::path(CLOTHSIM_SOURCE_DIR) / "tests/meshes_bad";
  std::ifstream manifest(dir / "expected.txt");
  REQUIRE(manifest);
  int cases = 0;
  for (std::string line; std::getline(manifest, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab1 = line.find('\t'), tab2 = line.find('\t', tab1 + 1);
    REQUIRE(tab2 != std::string::npos);
    const std::string scene = (dir / line.substr(0, tab1)).string();
    // A bad mesh never needs gigabytes: the limit makes a header that lies about its counts
    // (which Assimp once allocated 17 GB for) fail here, not take the machine's memory.
    const Result r = run({"simulate", scene, "--frames", "1", "--backend", "cpu"}, address_space_limit("4000000"));
    INFO(line << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains(scene));
    CHECK_THAT(r.err, Catch::Contains(line.substr(tab1 + 1, tab2 - tab1 - 1)));
    CHECK_THAT(r.err, Catch::Contains(line.substr(tab2 + 1)));
    ++cases;
  }
  CHECK(cases >= 15);
}

TEST_CASE("a missing scene file exits 2 naming the file", "[cli]") {
  const std::string path = (kBad / "there_is_no_such_scene.json").string();
  const Result r = run({"simulate", path, "--frames", "1", "--backend", "cpu"});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(path));
}

TEST_CASE("an unknown flag exits 2 and points to the usage", "[cli]") {
  const Result r = run({"simulate", (kSource / "scenes/pinned2.json").string(), "--frobnicate"});
  INFO(r.both());
  CHECK(r.code == 2);
  CHECK_THAT(r.both(), Catch::Contains("--frobnicate"));
  CHECK_THAT(r.both(), Catch::Contains("--help"));
}

TEST_CASE("a missing value for --frames exits 2", "[cli]") {
  const Result r = run({"simulate", (kSource / "scenes/pinned2.json").string(), "--frames"});
  INFO(r.both());
  CHECK(r.code == 2);
  CHECK_THAT(r.both(), Catch::Contains("--frames"));
}

TEST_CASE("a bad value for --frames or --backend exits 2", "[cli]") {
  const std::string scene = (kSource / "scenes/pinned2.json").string();
  CHECK(run({"simulate", scene, "--frames", "many", "--backend", "cpu"}).code == 2);
  CHECK(run({"simulate", scene, "--frames", "-1", "--backend", "cpu"}).code == 2);
  CHECK(run({"simulate", scene, "--frames", "1", "--backend", "quantum"}).code == 2);
}

TEST_CASE("an unknown scene for the default viewer command exits 2", "[cli]") {
  // No command means the viewer; a missing scene file is bad input whatever the display.
  CHECK(run({"frobnicate"}).code == 2);
  CHECK(run({"simulate", "--frobnicate"}).code == 2);
}

TEST_CASE("asking for --help shows the usage and exits 0", "[cli]") {
  const Result top = run({"--help"});
  INFO(top.both());
  CHECK(top.code == 0);
  CHECK_THAT(top.both(), Catch::Contains("Usage"));
  CHECK_THAT(top.both(), Catch::Contains("simulate"));

  const Result sim = run({"simulate", "--help"});
  INFO(sim.both());
  CHECK(sim.code == 0);
  CHECK_THAT(sim.both(), Catch::Contains("Usage"));
  CHECK_THAT(sim.both(), Catch::Contains("--frames"));
  CHECK_THAT(sim.both(), Catch::Contains("--backend"));
  CHECK_THAT(sim.both(), Catch::Contains("--export"));
  CHECK_THAT(sim.both(), Catch::Contains("--set"));
}

TEST_CASE("a bad --set exits 2 naming the key", "[cli]") {
  const std::string scene = (kSource / "scenes/pinned2.json").string();
  const Result r = run({"simulate", scene, "--frames", "1", "--backend", "cpu", "--set", "cloth.ks=abc"});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("cloth.ks"));
  CHECK_THAT(r.err, Catch::Contains(scene));

  const Result unknown = run({"simulate", scene, "--frames", "1", "--backend", "cpu", "--set", "cloth.kss=1"});
  CHECK(unknown.code == 2);
  CHECK_THAT(unknown.err, Catch::Contains("cloth.kss: unknown key"));

  const Result no_eq = run({"simulate", scene, "--frames", "1", "--backend", "cpu", "--set", "cloth.ks"});
  CHECK(no_eq.code == 2);
  CHECK_THAT(no_eq.err, Catch::Contains("cloth.ks"));
}

TEST_CASE("simulate --export writes the cloth as OBJ in particle order", "[cli]") {
  TempFile obj("pinned2.obj");
  const Result r = run({"simulate", (kSource / "scenes/pinned2.json").string(), "--frames", "2", "--backend",
                        "cpu", "--export", obj.path.string(), "--set", "cloth.ks=5000"});
  INFO(r.both());
  REQUIRE(r.code == 0);
  REQUIRE(fs::exists(obj.path));

  std::ifstream in(obj.path);
  std::string line, kinds;  // the order in which line kinds first appear
  int v = 0, vt = 0, vn = 0, f = 0, min_index = 1 << 30, max_index = 0;
  std::string first_v, first_f;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string kind;
    ls >> kind;
    if (kind.empty() || kind[0] == '#') continue;
    if (kinds.empty() || kinds.substr(kinds.rfind(' ') + 1) != kind) kinds += " " + kind;
    if (kind == "v") { if (v++ == 0) first_v = line; }
    else if (kind == "vt") ++vt;
    else if (kind == "vn") ++vn;
    else if (kind == "f") {
      if (f++ == 0) first_f = line;
      std::string corner;
      int corners = 0;
      while (ls >> corner) {
        ++corners;
        const int idx = std::stoi(corner);  // "i/i/i": the position index comes first
        min_index = std::min(min_index, idx);
        max_index = std::max(max_index, idx);
      }
      CHECK(corners == 3);
    } else {
      FAIL("unexpected OBJ line: " << line);
    }
  }
  CHECK(kinds == " v vt vn f");  // each kind in one block, in the order of docs/design.md §3
  CHECK(v == 2500);
  CHECK(vt == 2500);
  CHECK(vn == 2500);
  CHECK(f == 2 * 49 * 49);
  CHECK(min_index == 1);
  CHECK(max_index == 2500);
  // Particle 0 is pinned at (0, 1, 0); the first triangle is (A, C, B) of cell (0, 0), 1-based.
  std::istringstream fv(first_v);
  std::string tag;
  double x = -1, y = -1, z = -1;
  fv >> tag >> x >> y >> z;
  CHECK(x == Approx(0).margin(1e-9));
  CHECK(y == Approx(1).margin(1e-9));
  CHECK(z == Approx(0).margin(1e-9));
  CHECK(first_f == "f 1/1/1 51/51/51 2/2/2");
}

// Nothing lost (docs/export.md): a file the user named is replaced only by a complete new
// one; the PC2 is streamed into NAME.pc2.partial and renamed when the run succeeds; the OBJ
// beside a PC2 never replaces another mesh the user did not name; and readers check sizes
// before they allocate.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "backend.hpp"
#include "export/checkpoint.hpp"
#include "analysis/diagnostics.hpp"
#include "io/output_file.hpp"
#include "io/point_cache.hpp"
#include "output_support.hpp"
#include "test_helpers.hpp"

using namespace clothsim;
namespace fs = std::filesystem;
using test::kDiverging;
using test::kSmall;
using test::listing;
using test::run_binary;
using test::put_file;
using test::slurp;

namespace {

struct TempDir : test::TempDir {
  explicit TempDir(const std::string& name) : test::TempDir("outputs", name) {}
};


std::string pc2_header_bytes(int32_t points, int32_t samples) {
  std::string h("POINTCACHE2\0", 12);
  const int32_t version = 1;
  const float start = 0, rate = 1;
  h.append(reinterpret_cast<const char*>(&version), 4);
  h.append(reinterpret_cast<const char*>(&points), 4);
  h.append(reinterpret_cast<const char*>(&start), 4);
  h.append(reinterpret_cast<const char*>(&rate), 4);
  h.append(reinterpret_cast<const char*>(&samples), 4);
  return h;
}

}  // namespace

TEST_CASE("a PC2 header claiming more points or samples than the file holds is refused before allocating",
          "[export][reader]") {
  TempDir dir("pc2_reader");
  const std::string huge = dir / "huge.pc2";
  std::string bytes = pc2_header_bytes(1 << 30, 1);  // 2^30 points: a 12 GiB sample
  bytes.resize(100, '\0');
  put_file(huge, bytes);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(read_pc2_header(huge), Catch::Contains(huge) && Catch::Contains("truncated") &&
                                               Catch::Contains("1073741824 points x 1 samples") &&
                                               Catch::Contains("the file has 100 bytes"));
  CHECK_THROWS_WITH(read_pc2_sample(huge, 0), Catch::Contains("truncated") && Catch::Contains("1073741824 points"));
  // Refused from the header alone: no 12 GiB allocated, filled or freed.
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::milliseconds(500));

  // No samples counted: the header is fine, but there is no sample 0 to allocate for.
  const std::string empty = dir / "empty.pc2";
  put_file(empty, pc2_header_bytes(1 << 30, 0));
  CHECK(read_pc2_header(empty).points == 1 << 30);
  CHECK_THROWS_WITH(read_pc2_sample(empty, 0), Catch::Contains("no sample 0"));
  const std::string negative = dir / "negative.pc2";
  put_file(negative, pc2_header_bytes(-5, 1) + std::string(60, '\0'));
  CHECK_THROWS_WITH(read_pc2_header(negative), Catch::Contains("corrupted header"));

  // One byte short of its last sample is truncated; a partial sample past the count is fine
  // (a cache read while it is written).
  const std::string cut = dir / "cut.pc2";
  put_file(cut, pc2_header_bytes(3, 2) + std::string(2 * 36 - 1, '\0'));
  CHECK_THROWS_WITH(read_pc2_header(cut), Catch::Contains("truncated"));
  put_file(cut, pc2_header_bytes(3, 2) + std::string(2 * 36 + 20, '\0'));
  CHECK(read_pc2_sample(cut, 1).size() == 3);
}

TEST_CASE("write_obj replaces the file only once complete, leaving no temporary", "[export][outputs]") {
  const Scene s = test::make_scene(7, 5, 0);
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  TempDir dir("obj");
  const std::string obj = dir / "cloth.obj";
  put_file(obj, "old\n");
  write_obj(obj, m, cpu.snapshot());
  CHECK(slurp(obj).rfind("# clothsim cloth, 7x5", 0) == 0);
  CHECK(listing(dir.path) == std::set<std::string>{"cloth.obj"});

  // A destination that cannot be replaced (a non-empty directory): refused, nothing left over.
  fs::create_directories(dir.path / "busy.obj" / "inside");
  CHECK_THROWS_WITH(write_obj(dir / "busy.obj", m, cpu.snapshot()), Catch::Contains("busy.obj"));
  CHECK(listing(dir.path) == std::set<std::string>{"busy.obj", "cloth.obj"});
  CHECK(fs::is_directory(dir.path / "busy.obj" / "inside"));

  // A state file likewise.
  fs::create_directories(dir.path / "busy.state" / "inside");
  CHECK_THROWS(write_checkpoint(dir / "busy.state",
                                {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, cpu.name(), cpu.save_state()}));
  write_checkpoint(dir / "good.state", {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, cpu.name(), cpu.save_state()});
  CHECK(listing(dir.path) == std::set<std::string>{"busy.obj", "busy.state", "cloth.obj", "good.state"});
}

TEST_CASE("a pending output is removed unless committed, and the old file stays", "[outputs]") {
  TempDir dir("pending");
  const std::string file = dir / "x.bin";
  put_file(file, "old");
  try {
    write_replacing(file, [&](const std::string& temp) {
      CHECK(fs::path(temp).parent_path() == dir.path);  // beside it: the rename stays on one file system
      put_file(temp, "half");
      throw std::runtime_error("disk full");
    });
  } catch (const std::runtime_error&) {
  }
  CHECK(slurp(file) == "old");
  CHECK(listing(dir.path) == std::set<std::string>{"x.bin"});
  write_replacing(file, [&](const std::string& temp) { put_file(temp, "new"); });
  CHECK(slurp(file) == "new");
  CHECK(listing(dir.path) == std::set<std::string>{"x.bin"});
}

TEST_CASE("simulate --export FILE.pc2 streams into FILE.pc2.partial and renames it when the run succeeds",
          "[export][outputs][cli]") {
  TempDir dir("pc2_rule");
  const std::string pc2 = dir / "run.pc2", obj = dir / "run.obj", partial = pc2 + ".partial";
  put_file(pc2, "an old cache");
  std::string out;
  REQUIRE(run_binary(fmt::format("simulate {} --frames 4 --export '{}'", kSmall, pc2), &out) == 0);
  CHECK(read_pc2_header(pc2).samples == 5);
  CHECK(listing(dir.path) == std::set<std::string>{"run.obj", "run.pc2"});

  // A run that diverges keeps the old cache and leaves the frames that passed in the partial.
  const std::string before = slurp(pc2), mesh_before = slurp(obj);
  CHECK(run_binary(fmt::format("simulate {} --frames 100 --export '{}'", kDiverging, pc2), &out) == 1);
  CHECK_THAT(out, Catch::Contains("the simulation diverged"));
  CHECK_THAT(out, Catch::Contains("kept " + partial) && Catch::Contains(pc2 + " is unchanged"));
  CHECK(slurp(pc2) == before);
  CHECK(slurp(obj) == mesh_before);  // the same cloth's start: already this mesh
  REQUIRE(fs::exists(partial));
  const Pc2Header h = read_pc2_header(partial);
  CHECK(h.samples >= 1);
  for (int k = 0; k < h.samples; ++k)
    for (const glm::vec3& p : read_pc2_sample(partial, k)) CHECK((std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)));
  CHECK(listing(dir.path) == std::set<std::string>{"run.obj", "run.pc2", "run.pc2.partial"});

  // The next good run replaces both the cache and the partial an earlier run left.
  REQUIRE(run_binary(fmt::format("simulate {} --frames 2 --export '{}'", kSmall, pc2), &out) == 0);
  CHECK(read_pc2_header(pc2).samples == 3);
  CHECK(listing(dir.path) == std::set<std::string>{"run.obj", "run.pc2"});

  // With no old cache, a diverged run says the cache was not written.
  CHECK(run_binary(fmt::format("simulate {} --frames 100 --export '{}'", kDiverging, dir / "fresh.pc2"), &out) == 1);
  CHECK_THAT(out, Catch::Contains(dir / "fresh.pc2 is not written"));
  CHECK(!fs::exists(dir / "fresh.pc2"));
  CHECK(fs::exists(dir / "fresh.pc2.partial"));
}

TEST_CASE("the mesh beside a PC2 never replaces another mesh the user did not name", "[export][outputs][cli]") {
  TempDir dir("pc2_mesh");
  const std::string pc2 = dir / "run.pc2", obj = dir / "run.obj";
  std::string out;
  // Someone's own run.obj (here: the last frame of another export): refused before the run.
  REQUIRE(run_binary(fmt::format("simulate {} --frames 3 --export '{}'", kSmall, obj), &out) == 0);
  const std::string theirs = slurp(obj);
  CHECK(run_binary(fmt::format("simulate {} --frames 3 --export '{}'", kSmall, pc2), &out) == 2);
  CHECK_THAT(out, Catch::Contains("error: --export " + pc2) && Catch::Contains(obj) &&
                      Catch::Contains("holds another mesh") && Catch::Contains("--export-mesh"));
  CHECK(slurp(obj) == theirs);
  CHECK(listing(dir.path) == std::set<std::string>{"run.obj"});

  // Named with --export-mesh, the mesh goes there and run.obj is left alone.
  REQUIRE(run_binary(fmt::format("simulate {} --frames 3 --export '{}' --export-mesh '{}'", kSmall, pc2, dir / "mesh.obj"),
                     &out) == 0);
  CHECK(slurp(obj) == theirs);
  CHECK(listing(dir.path) == std::set<std::string>{"mesh.obj", "run.obj", "run.pc2"});
  // A named mesh is the user's to replace.
  put_file(dir / "mesh.obj", "stale");
  REQUIRE(run_binary(fmt::format("simulate {} --frames 1 --export '{}' --export-mesh '{}'", kSmall, pc2, dir / "mesh.obj"),
                     &out) == 0);
  CHECK(slurp(dir / "mesh.obj").rfind("# clothsim cloth", 0) == 0);

  // Absent: written. Already this mesh (a rerun, here of another length): left as it was.
  fs::remove(obj);
  REQUIRE(run_binary(fmt::format("simulate {} --frames 2 --export '{}'", kSmall, pc2), &out) == 0);
  const std::string mesh = slurp(obj);
  const auto mtime = fs::last_write_time(obj);
  REQUIRE(run_binary(fmt::format("simulate {} --frames 5 --export '{}'", kSmall, pc2), &out) == 0);
  CHECK_THAT(out, Catch::Contains("already this mesh"));
  CHECK(slurp(obj) == mesh);
  CHECK(fs::last_write_time(obj) == mtime);
  // Another cloth is another mesh.
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export '{}' --set cloth.width=2", kSmall, pc2), &out) == 2);
  CHECK(slurp(obj) == mesh);
  // --export-mesh belongs to a point cache.
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export '{}' --export-mesh '{}'", kSmall, dir / "x.obj",
                               dir / "m.obj"),
                   &out) == 2);
  CHECK_THAT(out, Catch::Contains("--export-mesh: needs --export FILE.pc2"));
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export '{}' --export-mesh /nonexistent/dir/m.obj", kSmall, pc2),
                   &out) == 2);
  CHECK_THAT(out, Catch::Contains("--export-mesh /nonexistent/dir/m.obj: the directory"));
}

TEST_CASE("every output of simulate lands under its own name with nothing left beside it", "[export][outputs][cli]") {
  TempDir dir("clean");
  std::string out;
  put_file(dir / "s.state", "an old state");
  put_file(dir / "last.obj", "an old mesh");
  REQUIRE(run_binary(fmt::format("simulate {} --frames 3 --export '{}' --save-state '{}'", kSmall, dir / "last.obj",
                                 dir / "s.state"),
                     &out) == 0);
  CHECK(read_checkpoint(dir / "s.state").state.frame == 3);
  CHECK(slurp(dir / "last.obj").rfind("# clothsim cloth", 0) == 0);
  REQUIRE(run_binary(fmt::format("simulate {} --frames 2 --export '{}'", kSmall, dir / "seq/"), &out) == 0);
  CHECK(listing(dir.path) == std::set<std::string>{"last.obj", "s.state", "seq"});
  CHECK(listing(dir.path / "seq") == std::set<std::string>{"frame_0000.obj", "frame_0001.obj", "frame_0002.obj"});
  // Paths that cannot be written are still exit 2 before the run.
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export '{}'", kSmall, dir / "seq"), &out) == 0);  // a DIR
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --save-state '{}'", kSmall, dir.path.string()), &out) == 2);
  CHECK_THAT(out, Catch::Contains("is a directory"));
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export /nonexistent/dir/run.pc2", kSmall), &out) == 2);
  CHECK_THAT(out, Catch::Contains("does not exist"));
}

// Taking the cloth elsewhere: the PC2 point cache and OBJ sequences that `simulate --export`
// writes as it goes, and checkpoints (`--save-state` / `--load-state`) that continue a run
// bit for bit.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "backend.hpp"
#include "export/checkpoint.hpp"
#include "export/frame_export.hpp"
#include "io/point_cache.hpp"
#include "file_support.hpp"
#include "test_helpers.hpp"

using namespace clothsim;
using test::read_obj_vertices;
namespace fs = std::filesystem;

namespace {

struct TempDir : test::TempDir {
  explicit TempDir(const std::string& name) : test::TempDir("export", name) {}
};

double max_diff(const std::vector<glm::vec3>& a, const std::vector<glm::dvec3>& b) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(double(a[i][c]) - b[i][c]));
  return m;
}

int run_binary(const std::string& args) {
  const std::string cmd = fmt::format("'{}' {} >/dev/null 2>&1", CLOTHSIM_BINARY, args);
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The pinned2 scene on a small odd grid, so the cloth swings and the run takes milliseconds.
const std::string kSmall = fmt::format(
    "'{}/scenes/pinned2.json' --set cloth.num_width_points=7 --set cloth.num_height_points=5 "
    "--set 'cloth.pinned=[[0,0],[6,0]]' --backend cpu",
    CLOTHSIM_SOURCE_DIR);

}  // namespace

TEST_CASE("a PC2 cache written sample by sample is valid after every sample", "[export]") {
  TempDir dir("pc2");
  const std::string path = dir / "c.pc2";
  Pc2Writer w(path, 3, 5.f, 2.f);
  for (int k = 0; k < 3; ++k) {
    w.add({glm::dvec4(k, 1, 2, 0), glm::dvec4(3, k, 5, 0), glm::dvec4(6, 7, k + 0.5, 1)});
    // Another reader sees the header's count and the samples it counts, mid-run.
    const Pc2Header h = read_pc2_header(path);
    CHECK(h.samples == k + 1);
    CHECK(fs::file_size(path) == 32 + size_t(k + 1) * 3 * 12);
  }
  w.close();
  std::ifstream in(path, std::ios::binary);
  char magic[12];
  in.read(magic, 12);
  CHECK(std::string(magic, 12) == std::string("POINTCACHE2\0", 12));
  const Pc2Header h = read_pc2_header(path);
  CHECK(h.version == 1);
  CHECK(h.points == 3);
  CHECK(h.start_frame == 5.f);
  CHECK(h.sample_rate == 2.f);
  CHECK(h.samples == 3);
  const auto last = read_pc2_sample(path, 2);
  CHECK(last[0] == glm::vec3(2, 1, 2));
  CHECK(last[2] == glm::vec3(6, 7, 2.5));
}

TEST_CASE("simulate --export FILE.pc2: the header is right and the last sample is the last frame's OBJ",
          "[export][cli]") {
  TempDir dir("cli_pc2");
  for (int every : {1, 2}) {
    INFO("--export-every " << every);
    const std::string pc2 = dir / fmt::format("run{}.pc2", every), seq = dir / fmt::format("seq{}/", every);
    REQUIRE(run_binary(fmt::format("simulate {} --frames 6 --export '{}' --export-every {}", kSmall, pc2, every)) == 0);
    REQUIRE(run_binary(fmt::format("simulate {} --frames 6 --export '{}' --export-every {}", kSmall, seq, every)) == 0);
    const Pc2Header h = read_pc2_header(pc2);
    CHECK(h.version == 1);
    CHECK(h.points == 35);
    CHECK(h.start_frame == 0.f);
    CHECK(h.sample_rate == float(every));
    CHECK(h.samples == 1 + 6 / every);
    CHECK(fs::file_size(pc2) == 32 + size_t(h.samples) * 35 * 12);
    // The OBJ sequence has the same frames, named by frame number.
    for (int f = 0; f <= 6; ++f)
      CHECK(fs::exists(fmt::format("{}frame_{:04d}.obj", seq, f)) == (f % every == 0));
    CHECK(max_diff(read_pc2_sample(pc2, h.samples - 1), read_obj_vertices(seq + "frame_0006.obj")) <= 1e-6);
    // The mesh beside the cache is the start state, in the same vertex order.
    const std::string mesh = fs::path(pc2).replace_extension(".obj").string();
    CHECK(max_diff(read_pc2_sample(pc2, 0), read_obj_vertices(mesh)) <= 1e-6);
    CHECK(max_diff(read_pc2_sample(pc2, 0), read_obj_vertices(seq + "frame_0000.obj")) <= 1e-6);
    // The cloth moved, so the comparison above means something.
    CHECK(max_diff(read_pc2_sample(pc2, h.samples - 1), read_obj_vertices(mesh)) > 1e-3);
  }
}

TEST_CASE("bad export and state paths are exit 2 before the run", "[export][cli]") {
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export /nonexistent/dir/out.pc2", kSmall)) == 2);
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export /nonexistent/dir/out.obj", kSmall)) == 2);
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --save-state /nonexistent/dir/s.state", kSmall)) == 2);
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export /proc/clothsim/", kSmall)) == 2);
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export out.obj --export-every 2", kSmall)) == 2);
}

namespace {

template <class R> void check_checkpoint_continues_bitwise() {
  const Scene s = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0],[6,0]]"});
  const ClothModel m = build_cloth(s);
  const int n = 8;
  CpuBackend<R> whole(s, m);
  for (int f = 0; f < 2 * n; ++f) whole.step_frame();

  TempDir dir("checkpoint");
  {
    CpuBackend<R> first(s, m);
    for (int f = 0; f < n; ++f) first.step_frame();
    write_checkpoint(dir / "half.state", {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, first.name(), first.save_state()});
  }
  const Checkpoint c = read_checkpoint(dir / "half.state");
  CpuBackend<R> second(s, m);
  check_fits(c, dir / "half.state", s, m, second.scalar_bytes(), second.name());
  second.load_state(c.state);
  for (int f = 0; f < n; ++f) second.step_frame();

  const SavedState a = whole.save_state(), b = second.save_state();
  CHECK(a.frame == 2 * n);
  CHECK(b.frame == 2 * n);
  CHECK(a.time == b.time);
  CHECK(a.positions == b.positions);
  CHECK(a.displacement == b.displacement);
  CHECK(whole.snapshot().pos != CpuBackend<R>(s, m).snapshot().pos);  // it moved
}

}  // namespace

TEST_CASE("2N frames equal N frames, saved, loaded and N more, bitwise (cpu double)", "[checkpoint]") {
  check_checkpoint_continues_bitwise<double>();
}

TEST_CASE("2N frames equal N frames, saved, loaded and N more, bitwise (cpu float)", "[checkpoint]") {
  check_checkpoint_continues_bitwise<float>();
}

TEST_CASE("a truncated, foreign or mismatched state file is refused with a message naming it", "[checkpoint]") {
  const Scene s = test::make_scene(7, 5, 0);
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  cpu.step_frame();
  TempDir dir("bad_state");
  const std::string good = dir / "good.state";
  write_checkpoint(good, {cloth_hash(m), m.nw, m.nh, pinned_count(m), "a.json", cpu.name(), cpu.save_state()});
  REQUIRE_NOTHROW(read_checkpoint(good));

  auto write_bytes = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  };
  std::stringstream whole;
  whole << std::ifstream(good, std::ios::binary).rdbuf();
  const std::string bytes = whole.str();

  auto refused = [](const std::string& path, const std::string& why) {
    INFO(path);
    CHECK_THROWS_WITH(read_checkpoint(path), Catch::Contains(path) && Catch::Contains(why));
  };
  for (size_t keep : {size_t(0), size_t(10), size_t(64), size_t(100), bytes.size() - 1})
    refused(write_bytes(fmt::format("cut{}.state", keep), bytes.substr(0, keep)), keep < 16 ? "not a clothsim state" : "truncated");
  refused(write_bytes("longer.state", bytes + "x"), "trailing bytes");
  refused(write_bytes("foreign.state", std::string(4096, 'z')), "not a clothsim state");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 1;
  refused(write_bytes("flipped.state", flipped), "checksum");
  refused(dir / "missing.state", "cannot open");

  const Checkpoint c = read_checkpoint(good);
  const Scene other = test::make_scene(9, 5, 0);
  const ClothModel om = build_cloth(other);
  CHECK_THROWS_WITH(check_fits(c, good, other, om, 8, "cpu (double)"),
                    Catch::Contains("different cloth") && Catch::Contains("7x5") && Catch::Contains("9x5") &&
                        Catch::Contains(fmt::format("{:016x}", cloth_hash(m))) &&
                        Catch::Contains(fmt::format("{:016x}", cloth_hash(om))));
  const Scene pinned = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0]]"});
  CHECK_THROWS_WITH(check_fits(c, good, pinned, build_cloth(pinned), 8, "x"), Catch::Contains("different cloth"));
  CHECK_THROWS_WITH(check_fits(c, good, s, m, 4, "gpu"), Catch::Contains("8-byte (double)") && Catch::Contains("gpu"));
  // What does not change the cloth still loads.
  const Scene stiffer = test::make_scene(7, 5, 0, {"cloth.ks=800", "cloth.damping=1", "cloth.density=200"});
  CHECK_NOTHROW(check_fits(c, good, stiffer, build_cloth(stiffer), 8, "cpu (double)"));
}

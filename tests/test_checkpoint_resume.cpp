// Checkpoints that record their substep length (state file version 2): a state loaded into a
// scene with another dt keeps the cloth's velocity, a version-1 file (no dt) still loads,
// moving, windy and fabric scenes continue bit for bit, and a state holding a non-finite time,
// position or displacement is refused naming the file.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "backend.hpp"
#include "export/checkpoint.hpp"
#include "analysis/diagnostics.hpp"
#include "test_helpers.hpp"

using namespace clothsim;
namespace fs = std::filesystem;

namespace {

struct TempDir : test::TempDir {
  explicit TempDir(const std::string& name) : test::TempDir("resume", name) {}
};

Scene scene_file(const std::string& name, const std::vector<std::string>& sets = {}) {
  return load_scene(fs::path(CLOTHSIM_SOURCE_DIR) / "scenes" / (name + ".json"), sets);
}

Checkpoint checkpoint_of(const Scene& s, const ClothModel& m, Backend& b) {
  return {cloth_hash(m), m.nw, m.nh, pinned_count(m), s.source, b.name(), b.save_state()};
}

std::string slurp(const std::string& path) {
  std::stringstream ss;
  ss << std::ifstream(path, std::ios::binary).rdbuf();
  return ss.str();
}

uint64_t fnv1a(const std::string& bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

// `clothsim ARGS` with stdout and stderr together in *output.
int run_binary(const std::string& args, std::string* output, const TempDir& dir) {
  const std::string log = dir / "run.log";
  const int status = std::system(fmt::format("'{}' {} >'{}' 2>&1", CLOTHSIM_BINARY, args, log).c_str());
  if (output) *output = slurp(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// N frames, saved to a file and read back, N more, against 2N straight: bitwise.
template <class R> void check_resumes_bitwise(const Scene& s, int n) {
  const ClothModel m = build_cloth(s);
  CpuBackend<R> whole(s, m);
  for (int f = 0; f < 2 * n; ++f) whole.step_frame();
  TempDir dir("bitwise");
  {
    CpuBackend<R> first(s, m);
    for (int f = 0; f < n; ++f) first.step_frame();
    write_checkpoint(dir / "half.state", checkpoint_of(s, m, first));
  }
  const Checkpoint c = read_checkpoint(dir / "half.state");
  CHECK(c.version == 4);
  CHECK(c.state.dt == s.dt());
  CpuBackend<R> second(s, m);
  check_fits(c, dir / "half.state", s, m, second.scalar_bytes(), second.name());
  second.load_state(c.state);
  for (int f = 0; f < n; ++f) second.step_frame();
  const SavedState a = whole.save_state(), b = second.save_state();
  CHECK(b.frame == 2 * n);
  CHECK(a.time == b.time);
  CHECK(test::mismatches(a.positions, b.positions) == 0);
  CHECK(test::mismatches(a.displacement, b.displacement) == 0);
  CHECK(whole.snapshot().pos != CpuBackend<R>(s, m).snapshot().pos);  // it moved
}

}  // namespace

TEST_CASE("save and resume is bitwise on a moving scene (living: wind, gusts, a moving sphere, moving pins)",
          "[checkpoint]") {
  const Scene s = scene_file("living");
  REQUIRE(s.cloth.pinned_motion);
  REQUIRE(s.spheres.at(0).motion);
  check_resumes_bitwise<double>(s, 12);
  check_resumes_bitwise<float>(s, 12);
}

TEST_CASE("save and resume is bitwise on a windy fabric scene (flag_pole) and on hang_xpbd",
          "[checkpoint][long]") {
  check_resumes_bitwise<double>(scene_file("flag_pole"), 6);
  check_resumes_bitwise<double>(scene_file("hang_xpbd"), 10);
  check_resumes_bitwise<float>(scene_file("hang_xpbd"), 10);
}

// fabric's predict reads the multigrid solve's offsets of the substep before: version 4 saves
// them, so its run resumes bit for bit too (a drop onto the sphere: the adaptive start in play).
TEST_CASE("save and resume is bitwise under the fabric solver (its solve offsets saved)", "[checkpoint][long]") {
  const Scene s = scene_file("sphere", {"simulation.solver=\"fabric\"", "cloth.density=0.15", "cloth.ks=5000"});
  check_resumes_bitwise<float>(s, 8);
  check_resumes_bitwise<double>(s, 8);
}

TEST_CASE("a state loaded with another substep length keeps the cloth's kinetic energy (pinned2, 30 -> 60 substeps)",
          "[checkpoint][long]") {
  // Without damping: the classic solver damps per substep (keep_velocity = 1 - damping / 100
  // each substep), so at the default 0.2 % twice the substeps take about 11 % more kinetic
  // energy out of a frame, whatever the state was loaded with. Undamped, what is left between
  // the two runs is the integration error of the substep length alone.
  const Scene s30 = scene_file("pinned2", {"simulation.simulation_steps=30", "cloth.damping=0"});
  const Scene s60 = scene_file("pinned2", {"simulation.simulation_steps=60", "cloth.damping=0"});
  const ClothModel m = build_cloth(s30);
  REQUIRE(cloth_hash(m) == cloth_hash(build_cloth(s60)));
  CpuBackend<double> straight(s30, m);
  for (int f = 0; f < 30; ++f) straight.step_frame();
  TempDir dir("dt");
  write_checkpoint(dir / "f30.state", checkpoint_of(s30, m, straight));
  const double ke30 = measure(s30, m, straight.snapshot()).kinetic;
  straight.step_frame();
  const double ke31 = measure(s30, m, straight.snapshot()).kinetic;
  REQUIRE(ke30 > 1e-4);  // swinging, so a wrong velocity shows

  const Checkpoint c = read_checkpoint(dir / "f30.state");
  REQUIRE(c.state.dt == s30.dt());
  CpuBackend<double> resumed(s60, m);
  resumed.load_state(c.state);
  // The displacements were halved exactly as rescale_displacement halves them: the same velocity.
  CHECK(measure(s60, m, resumed.snapshot()).kinetic == Approx(ke30).epsilon(1e-12));
  resumed.step_frame();
  const double ke31_60 = measure(s60, m, resumed.snapshot()).kinetic;
  INFO("frame 31: kinetic " << ke31 << " J with 30 substeps all along, " << ke31_60 << " J resumed at 60");
  CHECK(std::abs(ke31_60 - ke31) <= 0.01 * ke31);

  // The same state with its dt unknown (as a version-1 file) loads unscaled: the velocity
  // doubles, which the check above would catch.
  SavedState unknown = c.state;
  unknown.dt = 0;
  CpuBackend<double> unscaled(s60, m);
  unscaled.load_state(unknown);
  CHECK(measure(s60, m, unscaled.snapshot()).kinetic == Approx(4 * ke30).epsilon(1e-9));
  unscaled.step_frame();
  CHECK(std::abs(measure(s60, m, unscaled.snapshot()).kinetic - ke31) > 0.1 * ke31);

  // End to end: simulate says so.
  std::string out;
  const std::string scene = fmt::format("'{}/scenes/pinned2.json' --backend cpu", CLOTHSIM_SOURCE_DIR);
  REQUIRE(run_binary(fmt::format("simulate {} --frames 2 --save-state '{}'", scene, dir / "cli.state"), &out, dir) == 0);
  REQUIRE(run_binary(fmt::format("simulate {} --frames 1 --load-state '{}' --set simulation.simulation_steps=60", scene,
                                 dir / "cli.state"),
                     &out, dir) == 0);
  CHECK_THAT(out, Catch::Contains("displacements scaled by 0.5"));
}

TEST_CASE("a version-1 state file (no substep length) still loads, its dt taken as the scene's", "[checkpoint]") {
  const Scene s = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0],[6,0]]"});
  const ClothModel m = build_cloth(s);
  CpuBackend<double> first(s, m);
  for (int f = 0; f < 5; ++f) first.step_frame();
  TempDir dir("v1");
  write_checkpoint(dir / "v4.state", checkpoint_of(s, m, first));
  // The same state as version 1 wrote it: 72-byte header (no dt, offset 68 reserved as zero),
  // version 1, the two streams (a version-4 file writes no multipliers, and a classic cloth no
  // offsets), its own checksum.
  const std::string v4 = slurp(dir / "v4.state");
  REQUIRE(v4.size() > 96);
  std::string v1 = v4.substr(0, 72) + v4.substr(88, v4.size() - 88 - 8);
  const uint32_t one = 1, zero = 0;
  std::memcpy(v1.data() + 16, &one, 4);
  std::memcpy(v1.data() + 68, &zero, 4);
  const uint64_t h = fnv1a(v1);
  v1.append(reinterpret_cast<const char*>(&h), 8);
  std::ofstream(dir / "v1.state", std::ios::binary) << v1;

  const Checkpoint c = read_checkpoint(dir / "v1.state");
  CHECK(c.version == 1);
  CHECK(c.state.dt == 0);
  CpuBackend<double> a(s, m), b(s, m);
  a.load_state(c.state);
  b.load_state(read_checkpoint(dir / "v4.state").state);
  a.step_frame();
  b.step_frame();
  CHECK(test::mismatches(a.save_state().positions, b.save_state().positions) == 0);
  // Saved again, it records this scene's dt.
  write_checkpoint(dir / "again.state", checkpoint_of(s, m, a));
  CHECK(read_checkpoint(dir / "again.state").state.dt == s.dt());

  // A version this clothsim does not know is refused, naming both.
  std::string v9 = v4;
  const uint32_t nine = 9;
  std::memcpy(v9.data() + 16, &nine, 4);
  std::ofstream(dir / "v9.state", std::ios::binary) << v9;
  CHECK_THROWS_WITH(read_checkpoint(dir / "v9.state"), Catch::Contains("version 9") && Catch::Contains("versions 1 to 4"));
}

TEST_CASE("a state with a NaN time or an Inf position or displacement is refused naming the file (exit 2)",
          "[checkpoint]") {
  // The cloth of the CLI run below: pinned2 on a 7x5 grid.
  const std::vector<std::string> sets = {"cloth.num_width_points=7", "cloth.num_height_points=5",
                                         "cloth.pinned=[[0,0],[6,0]]"};
  const Scene s = scene_file("pinned2", sets);
  const ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  cpu.step_frame();
  TempDir dir("nonfinite");
  auto write_with = [&](const std::string& name, auto&& spoil) {
    Checkpoint c = checkpoint_of(s, m, cpu);
    spoil(c.state);
    write_checkpoint(dir / name, c);  // a valid checksum: only the numbers are wrong
    return dir / name;
  };
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::string nan_time = write_with("nan_time.state", [&](SavedState& st) { st.time = nan; });
  const std::string inf_pos = write_with("inf_pos.state", [&](SavedState& st) {
    std::memcpy(st.positions.data() + (4 * 17 + 1) * sizeof(double), &inf, sizeof inf);  // particle 17, y
  });
  const std::string nan_disp = write_with("nan_disp.state", [&](SavedState& st) {
    std::memcpy(st.displacement.data() + (4 * 3 + 2) * sizeof(double), &nan, sizeof nan);  // particle 3, z
  });
  const std::string bad_dt = write_with("bad_dt.state", [&](SavedState& st) { st.dt = -1; });
  CHECK_THROWS_WITH(read_checkpoint(nan_time), Catch::Contains(nan_time) && Catch::Contains("time is nan"));
  CHECK_THROWS_WITH(read_checkpoint(inf_pos),
                    Catch::Contains(inf_pos) && Catch::Contains("position of particle 17 has y = inf"));
  CHECK_THROWS_WITH(read_checkpoint(nan_disp),
                    Catch::Contains(nan_disp) && Catch::Contains("displacement of particle 3 has z = nan"));
  CHECK_THROWS_WITH(read_checkpoint(bad_dt), Catch::Contains(bad_dt) && Catch::Contains("substep length is -1"));

  const std::string scene = fmt::format("'{}/scenes/pinned2.json' --backend cpu --set cloth.num_width_points=7 "
                                        "--set cloth.num_height_points=5 --set 'cloth.pinned=[[0,0],[6,0]]'",
                                        CLOTHSIM_SOURCE_DIR);
  std::string out;
  write_checkpoint(dir / "ok.state", checkpoint_of(s, m, cpu));
  REQUIRE(run_binary(fmt::format("simulate {} --frames 1 --load-state '{}'", scene, dir / "ok.state"), &out, dir) == 0);
  for (const std::string& bad : {nan_time, inf_pos}) {
    INFO(bad);
    CHECK(run_binary(fmt::format("simulate {} --frames 1 --load-state '{}'", scene, bad), &out, dir) == 2);
    CHECK_THAT(out, Catch::Contains("error: --load-state " + bad));
  }
}

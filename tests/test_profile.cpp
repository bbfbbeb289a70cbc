// simulate --profile (host/core/reference/pass_profile.hpp): every pass's own time, a pass
// timed inside another taken off the outer's row, and a profiled run the same bits as one that
// is not. The GPU's rows are tests/test_gpu_profile.cpp's.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "test_helpers.hpp"

using namespace clothsim;

namespace {

// A drop onto a sphere that rises (a keyframed collider: the substep's control runs too).
const char* const kRisingSphere = R"({
  "cloth": {"width": 0.5, "height": 0.5, "num_width_points": 9, "num_height_points": 9,
            "thickness": 0.004, "orientation": 0},
  "sphere": {"origin": [0.25, 0.7, 0.25], "radius": 0.2, "friction": 0.3,
             "motion": {"keyframes": [[0, [0.25, 0.7, 0.25]], [1, [0.25, 0.8, 0.25]]]}},
  "simulation": {"solver": "fabric", "self_collision": true}
})";

const PassProfile::Row* row_of(const PassProfile& p, const std::string& name) {
  for (const PassProfile::Row& r : p.rows())
    if (r.name == name) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("a pass timed inside another is its own row and the outer keeps the rest", "[profile]") {
  using namespace std::chrono;
  PassProfile p;
  const auto t0 = steady_clock::now();
  profiled(&p, "outer", [&] {
    profiled(&p, "inner", [] { std::this_thread::sleep_for(milliseconds(30)); });
    profiled(&p, "inner", [] { std::this_thread::sleep_for(milliseconds(10)); });
  });
  profiled(&p, "after", [] {});
  const double wall = duration<double>(steady_clock::now() - t0).count();
  REQUIRE(p.rows().size() == 3);
  CHECK(p.rows()[0].name == "inner");  // in the order the passes first ended
  CHECK(p.rows()[0].runs == 2);
  CHECK(p.rows()[0].seconds >= 0.040);
  CHECK(p.rows()[1].name == "outer");
  CHECK(p.rows()[1].runs == 1);
  CHECK(p.rows()[1].seconds >= 0.0);
  CHECK(p.rows()[1].seconds < p.rows()[0].seconds);  // the sleeps are not the outer's
  CHECK(p.total_seconds() <= wall);
  // Without a profile the function still runs, once.
  int runs = 0;
  profiled(nullptr, "x", [&] { ++runs; });
  CHECK(runs == 1);
}

TEST_CASE("the reference profiled runs every pass it times and gives the same bits", "[profile]") {
  const Scene s = parse_scene(kRisingSphere, "rising.json");
  const ClothModel m = build_cloth(s);
  CpuBackend<float> plain(s, m), timed(s, m);
  PassProfile p;
  timed.set_profile(&p);
  constexpr int kFrames = 6;
  for (int f = 0; f < kFrames; ++f) plain.step_frame(), timed.step_frame();
  timed.set_profile(nullptr);
  timed.step_frame(), plain.step_frame();  // no longer timed
  CHECK(plain.state().pos == timed.state().pos);
  CHECK(plain.state().disp == timed.state().disp);
  const int64_t substeps = int64_t(kFrames) * s.simulation.simulation_steps;
  for (const char* name : {"substep control", "predict", "collide_self", "collide_objects", "solve_multigrid",
                           "enforce_stretch_limit"}) {
    INFO(name);
    const PassProfile::Row* r = row_of(p, name);
    REQUIRE(r != nullptr);
    CHECK(r->runs == substeps);
  }
  for (const char* name : {"compute_normals", "check_divergence"}) {
    INFO(name);
    REQUIRE(row_of(p, name) != nullptr);
    CHECK(row_of(p, name)->runs == kFrames);
  }
  CHECK(row_of(p, "advance") == nullptr);  // fabric predicts
  CHECK(row_of(p, "skin_colliders") == nullptr);
}

TEST_CASE("simulate --profile prints each pass's ms per frame and --stats-json keeps them", "[profile][cli]") {
  test::TempDir dir("profile", "cli");
  const std::string scene = dir / "rising.json", json = dir / "stats.json", log = dir / "out.txt";
  std::ofstream(scene) << kRisingSphere;
  const int status = std::system(fmt::format("'{}' simulate '{}' --backend cpu --frames 4 --profile --stats-json '{}' >'{}' 2>&1",
                                             CLOTHSIM_BINARY, scene, json, log)
                                     .c_str());
  std::stringstream out;
  out << std::ifstream(log).rdbuf();
  INFO(out.str());
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  CHECK(out.str().find("profile           4 frames") != std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
  REQUIRE(j.contains("pass_ms_per_frame"));
  double sum = 0;
  for (const char* name : {"predict", "collide_objects", "solve_multigrid", "compute_normals"}) {
    INFO(name);
    REQUIRE(j["pass_ms_per_frame"].contains(name));
    sum += j["pass_ms_per_frame"][name].get<double>();
    // Printed as a row: the name, then its ms.
    CHECK(out.str().find(fmt::format("  {:32} ", name)) != std::string::npos);
  }
  CHECK(out.str().find("all passes") != std::string::npos);
  CHECK(sum <= j["ms_per_frame"].get<double>());  // the rows are parts of the frames' wall time
}

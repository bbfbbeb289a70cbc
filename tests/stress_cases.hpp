// Stress: 10,000 substeps of a 7x5 cloth with extreme but legal parameters, on any backend.
// Each case either stays finite and inside the divergence limits the whole run, or stops with
// the divergence message and a finite last good frame; which one is part of the case.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "backend.hpp"
#include "test_helpers.hpp"

namespace clothsim::test {

struct StressCase {
  std::vector<std::string> sets;  // --set overrides of a 7x5 cloth
  std::string colliders;          // JSON members after "cloth", e.g. ", \"sphere\": {...}"
  int orientation = 0;
  int steps = 100, frames = 100;  // steps * frames = 10,000 substeps
  bool diverges = false;          // the expected outcome
};

inline constexpr int kStressSubsteps = 10000;

inline std::string all_pins(int nw, int nh) {
  std::string pins;
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) pins += fmt::format("{}[{},{}]", pins.empty() ? "" : ",", x, y);
  return "cloth.pinned=[" + pins + "]";
}

// The cases, by name. Self-collision is off except where it is the point: on llvmpipe the
// run time is the number of dispatches.
inline StressCase stress_case(const std::string& name) {
  const std::string steps = "simulation.simulation_steps=", no_self = "simulation.self_collision=false";
  const std::string sphere = R"(, "sphere": {"origin": [0.5, 0.2, 0.5], "radius": 0.2, "friction": %F%},
                                  "plane": {"point": [0, -0.2, 0], "normal": [0, 1, 0], "friction": %F%})";
  auto with_friction = [&](const char* f) {
    std::string s = sphere;
    for (size_t at; (at = s.find("%F%")) != std::string::npos;) s.replace(at, 3, f);
    return s;
  };
  // Light particles (density 1: 29 g each) make ks 1e6 stiff: stable below about 85 us.
  if (name == "stiff with enough substeps")
    return {{"cloth.ks=1e6", "cloth.density=1", "cloth.pinned=[[0,0],[6,0]]", steps + "250", no_self}, "", 1, 250, 40};
  if (name == "far too stiff for its substeps")
    return {{"cloth.ks=1e9", "cloth.pinned=[[0,0],[6,0]]", steps + "25", no_self}, "", 1, 25, 400, true};
  if (name == "frictionless colliders")
    return {{steps + "100", no_self}, with_friction("0"), 0};
  if (name == "colliders with full friction")
    return {{steps + "100", no_self}, with_friction("1"), 0};
  if (name == "zero gravity, no damping")
    return {{"simulation.gravity=[0,0,0]", "cloth.damping=0", steps + "100", no_self}, "", 1};
  if (name == "everything pinned")
    return {{all_pins(7, 5), "cloth.ks=1e6", steps + "100", no_self}, with_friction("0.5"), 1};
  if (name == "nothing pinned, self-collision on a plane")
    return {{"cloth.damping=0", steps + "100"}, R"(, "plane": {"point": [0, 0.9, 0], "normal": [0, 1, 0], "friction": 0})",
            0};
  if (name == "starting inside a sphere")
    return {{steps + "100", no_self}, R"(, "sphere": {"origin": [0.5, 1.0, 0.5], "radius": 1.0, "friction": 0.5})", 0};
  if (name == "a plane through the cloth")
    return {{"cloth.pinned=[[0,0],[6,0]]", steps + "100", no_self},
            R"(, "plane": {"point": [0.5, 1.0, 0.5], "normal": [1, 1, 0], "friction": 0.2})", 0};
  FAIL("no stress case named " << name);
  return {};
}

inline Scene stress_scene(const StressCase& c) { return make_scene(7, 5, c.orientation, c.sets, c.colliders); }

struct StressOutcome {
  std::optional<std::string> message;  // the divergence message, if the run stopped
  int failed_frame = 0;                // the frame it names
  int frames = 0;                      // frames run
  int checks = 0;                      // frame checks taken (each frame exactly once)
  ClothSnapshot last;                  // the state when the run ended
  ClothSnapshot good;                  // the last good frame
  int good_frame = -1;
};

// Runs the case like `clothsim simulate`: one frame at a time, each frame's check taken as it
// arrives, stopping at the first failure.
inline StressOutcome run_stress(Backend& backend, const Scene& scene, const ClothModel& model, const StressCase& c) {
  REQUIRE(c.steps * c.frames == kStressSubsteps);
  REQUIRE(scene.simulation.simulation_steps == c.steps);
  StressOutcome out;
  auto look = [&](bool all) {
    for (const FrameCheck& check : backend.take_checks(all)) {
      CHECK(check.frame == ++out.checks);
      if (out.message) continue;
      out.message = divergence_message(scene, model, check);
      if (out.message) out.failed_frame = check.frame;
    }
  };
  for (int f = 1; f <= c.frames && !out.message; ++f) {
    backend.step_frame();
    out.frames = f;
    look(false);
    CHECK(out.checks >= f - 1);  // at most one frame late
  }
  look(true);
  out.last = backend.snapshot();
  out.good = backend.last_good(&out.good_frame);
  return out;
}

inline bool all_finite(const ClothSnapshot& s) {
  for (auto& p : s.pos)
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(p[k])) return false;
  return true;
}

// The checks every case shares.
inline void check_stress_outcome(const StressCase& c, const StressOutcome& out) {
  INFO("message: " << out.message.value_or("(none)"));
  CHECK(all_finite(out.good));
  if (!c.diverges) {
    CHECK_FALSE(out.message.has_value());
    CHECK(out.frames == c.frames);
    CHECK(out.checks == c.frames);
    CHECK(all_finite(out.last));
    CHECK(out.good_frame == c.frames);
    return;
  }
  REQUIRE(out.message.has_value());
  CHECK_THAT(*out.message, Catch::StartsWith(fmt::format("the simulation diverged at frame {}:", out.failed_frame)));
  CHECK_THAT(*out.message, Catch::Contains("--set simulation.simulation_steps="));
  CHECK(out.frames <= out.failed_frame + 1);  // stopped at most one frame late
  CHECK(out.good_frame == out.failed_frame - 1);
}

}  // namespace clothsim::test

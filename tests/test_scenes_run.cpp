// Every shipped scene loads and runs with finite results.
#include <catch2/catch.hpp>

#include <filesystem>

#include "backend.hpp"

using namespace clothsim;

TEST_CASE("every scene under scenes/ loads and runs 30 frames with finite results", "[scenes][long]") {
  int scenes = 0;
  for (auto& entry : std::filesystem::directory_iterator(std::filesystem::path(CLOTHSIM_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    DYNAMIC_SECTION(entry.path().filename().string()) {
      // Large demo cloths run one frame of two substeps on the CPU: the point is that they
      // load and stay finite; their behaviour is shown by rendering them.
      const bool large = load_scene(entry.path()).particle_count() > 10000;
      Scene s = load_scene(entry.path(), large ? std::vector<std::string>{"simulation.simulation_steps=2"}
                                               : std::vector<std::string>{});
      ClothModel m = build_cloth(s);
      const int frames = large ? 1 : 30;
      CpuBackend<float> cpu(s, m);
      for (int f = 1; f <= frames; ++f) {
        cpu.step_frame();
        for (const FrameCheck& check : cpu.take_checks(true)) {
          CHECK(check.frame == f);
          REQUIRE_FALSE(divergence_message(s, m, check).has_value());
        }
      }
      CHECK(measure(s, m, cpu.snapshot()).finite);
    }
    ++scenes;
  }
  CHECK(scenes >= 5);
}

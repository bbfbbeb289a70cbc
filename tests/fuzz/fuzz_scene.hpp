// The scene-loader fuzz target's input format and property check (fuzz_scene.cpp), shared by
// the libFuzzer binary and the replay runner.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace clothsim::fuzz {

struct Input {
  std::string json;                    // bytes before the first NUL
  std::vector<std::string> overrides;  // the lines after it ('\n' or NUL separated, empty skipped)
};
Input split_input(const uint8_t* data, size_t size);

struct Outcome {
  bool loaded = false;  // parse_scene returned a valid scene
  std::string error;    // else the SceneError message
};
// Runs one input; aborts when the property is violated (see fuzz_scene.cpp).
Outcome run_one(const uint8_t* data, size_t size);

}  // namespace clothsim::fuzz

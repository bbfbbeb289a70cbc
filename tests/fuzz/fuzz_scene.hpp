// The scene-loader fuzz target's input format (fuzz_scene.cpp); its entry point, run_scene, is
// in fuzz_targets.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"  // run_scene

namespace clothsim::fuzz {

struct Input {
  std::string json;                    // bytes before the first NUL
  std::vector<std::string> overrides;  // the lines after it ('\n' or NUL separated, empty skipped)
};
Input split_input(const uint8_t* data, size_t size);

}  // namespace clothsim::fuzz

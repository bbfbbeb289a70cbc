// The fuzz targets' entry points, shared by the libFuzzer binaries (one per target) and the
// replay runner (replay_main.cpp): each runs one input through a loader and checks its
// property, aborting when it is violated (the property is described in each target's file).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace clothsim::fuzz {

struct Outcome {
  bool loaded = false;  // the loader returned a value that passed the property's checks
  std::string error;    // else the message of the loader's own error (the target's error type)
};

// Scene JSON plus --set overrides into parse_scene (fuzz_scene.cpp): SceneError.
Outcome run_scene(const uint8_t* data, size_t size);
// A state file into read_checkpoint (fuzz_state.cpp): CheckpointError.
Outcome run_state(const uint8_t* data, size_t size);
// A PC2 point cache into read_pc2_header and read_pc2_sample (fuzz_pc2.cpp): Pc2Error.
Outcome run_pc2(const uint8_t* data, size_t size);

}  // namespace clothsim::fuzz

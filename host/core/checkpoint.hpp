// Checkpoints (`simulate --save-state / --load-state`): a run's raw state streams, so that
// N frames, saved, loaded and N more frames are bit for bit the same as 2N frames.
// The streams are kept in the backend's own scalar (float on the GPU, float or double on the
// CPU) as raw bits; nothing is converted, so a state only loads into a backend of its scalar.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cloth.hpp"
#include "reference.hpp"
#include "scene.hpp"

namespace clothsim {

// What a backend hands out and takes back. Backend-neutral: the scalars are raw bytes.
struct SavedState {
  int scalar_bytes = 0;     // 4 (float) or 8 (double)
  int64_t frame = 0;        // frames simulated since the initial state
  double time = 0;          // simulated seconds
  std::vector<uint8_t> positions;       // 4 scalars per particle: x, y, z, inverse mass
  std::vector<uint8_t> displacement;  // 4 scalars per particle: what the integrator carries
                                        // besides the positions (see velocity_stream)
  size_t particles() const { return scalar_bytes ? positions.size() / (4 * size_t(scalar_bytes)) : 0; }
};

// The one place that knows which State members are saved (positions and State::disp);
// everything else goes through these two.
template <class R> SavedState save_streams(const State<R>& s, int64_t frame, double time);
// Into a state of the same cloth: xyz and the displacements bit for bit; the inverse masses
// (w) stay those of `s`, i.e. of the scene being run, so a changed density takes effect.
template <class R> void load_streams(const SavedState& saved, State<R>& s);

// Identifies "the same cloth": the grid, its start positions (width, height, orientation)
// and its pins, the things that decide which particle is which and which springs exist.
// Material and scene parameters (ks, density, damping, colliders, substeps, ...) are not
// part of it: a state may be continued under different ones.
uint64_t cloth_hash(const ClothModel& model);
int pinned_count(const ClothModel& model);

// A state file: the state plus what it belongs to.
struct Checkpoint {
  uint64_t cloth = 0;      // cloth_hash of the cloth it was saved from
  int nw = 0, nh = 0;
  int pins = 0;            // pinned particles, for messages
  std::string scene;       // the scene it was saved from, for messages
  std::string backend;     // the backend's name, for messages
  SavedState state;
};

// A state file that cannot be read or does not fit: the message names the file and why.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Written to PATH.tmp and renamed, so an interrupted save never leaves half a file.
void write_checkpoint(const std::string& path, const Checkpoint& c);
// Checks magic, version, sizes and the checksum: a truncated or foreign file throws.
Checkpoint read_checkpoint(const std::string& path);
// Throws unless `c` is of this cloth (cloth_hash) and of a backend with `scalar_bytes`
// scalars; the message names both sides.
void check_fits(const Checkpoint& c, const std::string& path, const Scene& scene, const ClothModel& model,
                int scalar_bytes, const std::string& backend);

}  // namespace clothsim

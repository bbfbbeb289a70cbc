// Checkpoints (`simulate --save-state / --load-state`): a run's raw state streams, so that
// N frames, saved, loaded and N more frames are bit for bit the same as 2N frames.
// The streams are kept in the backend's own scalar (float on the GPU, float or double on the
// CPU) as raw bits; nothing is converted, so a state only loads into a backend of its scalar.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include "cloth/cloth.hpp"
#include "reference/reference.hpp"
#include "scene/scene.hpp"

namespace clothsim {

// What a backend hands out and takes back. Backend-neutral: the scalars are raw bytes.
struct SavedState {
  int scalar_bytes = 0;     // 4 (float) or 8 (double)
  int64_t frame = 0;        // frames simulated since the initial state
  double time = 0;          // simulated seconds
  double dt = 0;            // the substep length the displacements are per (s); 0 = unknown
                            // (a version-1 file): taken as the loading scene's
  std::vector<uint8_t> positions;       // 4 scalars per particle: x, y, z, inverse mass
  std::vector<uint8_t> displacement;  // 4 scalars per particle: what the integrator carries
                                        // besides the positions (see velocity_stream)
  std::vector<uint8_t> multipliers;   // 4 scalars per spring: the removed xpbd solver's (read, ignored)
                                      // (State::lambda); empty from a version 1 or 2 file
  std::vector<uint8_t> offsets;       // 4 scalars per particle: the multigrid solve's offsets,
                                      // which fabric's predict reads (State::offset); empty for
                                      // the other solvers and from a version 1 to 3 file
  size_t particles() const { return scalar_bytes ? positions.size() / (4 * size_t(scalar_bytes)) : 0; }
};

// The one place that knows which State members are saved (positions and State::disp);
// everything else goes through these two.
// `dt`: the substep length the state's displacements are per (the scene's dt()).
template <class R> SavedState save_streams(const State<R>& s, int64_t frame, double time, double dt);
// Into a state of the same cloth: xyz and the displacements bit for bit; the inverse masses
// (w) stay those of `s`, i.e. of the scene being run, so a changed density takes effect.
// `dt` is the substep length of the scene being run: a state saved with another one has its
// displacements rescaled by dt / saved.dt (rescale_displacement), so the cloth keeps its
// velocity; with the same length (or an unknown one, saved.dt = 0) they load bit for bit.
template <class R> void load_streams(const SavedState& saved, State<R>& s, double dt);

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
  int version = 2;         // of the file it was read from (1: no dt recorded)
};

// A state file that cannot be read or does not fit: the message names the file and why.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Written to a temporary beside PATH (output_file.hpp) and renamed, so an interrupted save
// never leaves half a file and a failed one leaves the old file.
void write_checkpoint(const std::string& path, const Checkpoint& c);
// Checks magic, version (1 or 2), sizes (against the file's, before allocating) and the
// checksum, then that the time, dt and every position and displacement are finite: a
// truncated, foreign or non-finite file throws, naming the file.
Checkpoint read_checkpoint(const std::string& path);
// The same from the `size` bytes of `in` (a file's whole contents, from position 0; what the
// path version reads, and the fuzz target, tests/fuzz/fuzz_state.cpp, calls without a file).
// `name` stands for the file in messages.
Checkpoint read_checkpoint(std::istream& in, uint64_t size, const std::string& name);
// Throws unless `c` is of this cloth (cloth_hash) and of a backend with `scalar_bytes`
// scalars; the message names both sides.
void check_fits(const Checkpoint& c, const std::string& path, const Scene& scene, const ClothModel& model,
                int scalar_bytes, const std::string& backend);

}  // namespace clothsim

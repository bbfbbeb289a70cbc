// libFuzzer target for the state-file reader (`simulate --load-state`): read_checkpoint.
//
// Input bytes: a state file, as --save-state writes it (format: host/core/export/checkpoint.cpp).
// Each input is read twice from memory, read_checkpoint(stream, size, "<fuzz>"): as it is, and
// with its last 8 bytes replaced by the FNV-1a checksum of the rest. Nearly every mutation
// breaks the checksum, so without the second read the checks after it (finite numbers, time,
// frame, dt) would almost never be reached.
//
// Property, for each read: read_checkpoint either returns a Checkpoint that agrees with the
// bytes field by field, decoded here independently from the format (magic, version 1, 2 or 3,
// 4- or 8-byte scalars, a grid of 3..kMaxParticles particles, the names, both streams, version
// 3's spring multipliers, and a file size of exactly header + names + streams + checksum, with a
// matching checksum), whose time, frame and dt are in range and whose every position,
// displacement and multiplier is finite; or it
// throws clothsim::CheckpointError whose message starts with the source name. In both cases
// the read allocates at most the input's size plus kSlackBytes (allocation_meter.hpp): a size
// taken from the header must be checked against the file's before anything is allocated from
// it. Anything else (another exception, a violated property) calls abort(), which libFuzzer
// reports as a crash; ASan/UBSan reports, hangs (-timeout) and OOMs are crashes too.
//
// The same code is built without libFuzzer into clothsim_fuzz_replay (replay_main.cpp), which
// ctest runs over tests/fuzz/seeds_state/ and tests/fuzz/regressions/state/ in every build.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include <fmt/format.h>

#include "allocation_meter.hpp"
#include "export/checkpoint.hpp"
#include "fuzz_targets.hpp"

namespace clothsim::fuzz {
namespace {

// What a read may allocate beyond the input's size: its error message and the exception object.
constexpr uint64_t kSlackBytes = 4096;

[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "fuzz_state: PROPERTY VIOLATED: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void expect(bool ok, const std::string& what) {
  if (!ok) violated(what);
}

template <class T> T get(const std::string& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

uint64_t fnv1a(const char* p, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ uint8_t(p[i])) * 0x100000001b3ull;
  return h;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The Checkpoint read from `b` is what the format says `b` holds.
void check_loaded(const Checkpoint& c, const std::string& b) {
  const SavedState& s = c.state;
  expect(b.size() >= 80 && std::memcmp(b.data(), "clothsim state\n", 16) == 0, "loaded without the magic");
  const uint32_t version = get<uint32_t>(b, 16);
  expect(version >= 1 && version <= 4, fmt::format("loaded a version-{} file", version));
  expect(c.version == int(version), "Checkpoint::version is the file's");
  const size_t header = version == 1 ? 72 : version <= 3 ? 80 : 88;
  expect(b.size() >= header, "loaded a file shorter than its header");
  const uint32_t scalar = get<uint32_t>(b, 20), nw = get<uint32_t>(b, 24), nh = get<uint32_t>(b, 28);
  expect(scalar == 4 || scalar == 8, fmt::format("loaded {}-byte scalars", scalar));
  expect(s.scalar_bytes == int(scalar), "scalar_bytes is the file's");
  expect(c.nw == int(nw) && c.nh == int(nh), "nw x nh is the file's");
  const uint64_t particles = uint64_t(nw) * nh;
  expect(nw >= 1 && nh >= 1 && particles >= 3 && particles <= uint64_t(kMaxParticles),
         fmt::format("loaded a {}x{} grid", nw, nh));
  expect(c.cloth == get<uint64_t>(b, 32), "the cloth hash is the file's");
  expect(s.frame == get<int64_t>(b, 40) && s.frame >= 0, "the frame is the file's and >= 0");
  expect(same_bits(s.time, get<double>(b, 48)) && std::isfinite(s.time) && s.time >= 0,
         "the time is the file's, finite and >= 0");
  const uint64_t scene_len = get<uint32_t>(b, 56), backend_len = get<uint32_t>(b, 60);
  expect(uint32_t(c.pins) == get<uint32_t>(b, 64), "the pinned count is the file's");
  // Version 3 keeps the xpbd springs' carried multipliers (4 scalars each) after the
  // displacements, their count at 68; before it that word was unused and the stream absent.
  const uint64_t multipliers = version >= 3 ? get<uint32_t>(b, 68) : 0;
  // Version 4 keeps the multigrid solve's offsets (4 scalars per particle, or none) after the
  // multipliers, their count at 80.
  const uint64_t offsets = version >= 4 ? get<uint32_t>(b, 80) : 0;
  expect(offsets == 0 || offsets == particles, "loaded offsets neither none nor one per particle");
  if (version == 1)
    expect(s.dt == 0, "a version-1 state has an unknown dt (0)");
  else
    expect(same_bits(s.dt, get<double>(b, 72)) && std::isfinite(s.dt) && s.dt > 0,
           "the dt is the file's, finite and > 0");

  const uint64_t stream = particles * 4 * scalar;
  const uint64_t multiplier_stream = multipliers * 4 * scalar, offset_stream = offsets * 4 * scalar;
  expect(uint64_t(b.size()) == header + scene_len + backend_len + 2 * stream + multiplier_stream + offset_stream + 8,
         "the file is exactly header + names + streams + checksum");
  expect(fnv1a(b.data(), b.size() - 8) == get<uint64_t>(b, b.size() - 8), "loaded with a wrong checksum");
  size_t at = header;
  expect(c.scene == b.substr(at, scene_len), "the scene name is the file's");
  at += scene_len;
  expect(c.backend == b.substr(at, backend_len), "the backend name is the file's");
  at += backend_len;
  expect(s.positions.size() == stream && s.displacement.size() == stream, "both streams hold nw x nh x 4 scalars");
  expect(s.particles() == particles, "SavedState::particles() is nw x nh");
  expect(std::memcmp(s.positions.data(), b.data() + at, stream) == 0, "the positions are the file's");
  expect(std::memcmp(s.displacement.data(), b.data() + at + stream, stream) == 0, "the displacements are the file's");
  // (An empty vector's data() may be null, which memcmp must not see even for 0 bytes.)
  expect(s.multipliers.size() == multiplier_stream &&
             (multiplier_stream == 0 ||
              std::memcmp(s.multipliers.data(), b.data() + at + 2 * stream, multiplier_stream) == 0),
         "the multipliers are the file's");
  expect(s.offsets.size() == offset_stream &&
             (offset_stream == 0 ||
              std::memcmp(s.offsets.data(), b.data() + at + 2 * stream + multiplier_stream, offset_stream) == 0),
         "the offsets are the file's");
  for (const std::vector<uint8_t>* bytes : {&s.positions, &s.displacement, &s.multipliers, &s.offsets})
    for (size_t i = 0; i < bytes->size(); i += scalar) {
      double v;
      if (scalar == 8) {
        std::memcpy(&v, bytes->data() + i, 8);
      } else {
        float f;
        std::memcpy(&f, bytes->data() + i, 4);
        v = f;
      }
      expect(std::isfinite(v), "loaded a state holding a NaN or Inf");
    }
}

Outcome read_one(const std::string& bytes) {
  std::istringstream in(bytes);  // made before the meter starts: its copy is the input's
  Outcome out;
  try {
    const Checkpoint c = [&] {
      AllocationMeter meter(bytes.size() + kSlackBytes, fmt::format("read_checkpoint on {} bytes", bytes.size()));
      return read_checkpoint(in, bytes.size(), "<fuzz>");
    }();
    check_loaded(c, bytes);
    out.loaded = true;
  } catch (const CheckpointError& e) {
    out.error = e.what();
    expect(out.error.rfind("<fuzz>: ", 0) == 0,
           "a CheckpointError message does not start with the source: " + out.error);
  } catch (const std::exception& e) {
    violated(std::string("an exception other than CheckpointError escaped read_checkpoint: ") + typeid(e).name() +
             ": " + e.what());
  } catch (...) {
    violated("a non-std exception escaped read_checkpoint");
  }
  return out;
}

}  // namespace

Outcome run_state(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const Outcome as_is = read_one(bytes);
  if (size >= 8) {
    const uint64_t h = fnv1a(bytes.data(), size - 8);
    std::memcpy(bytes.data() + size - 8, &h, 8);
    read_one(bytes);
  }
  return as_is;
}

}  // namespace clothsim::fuzz

#ifdef CLOTHSIM_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  clothsim::fuzz::run_state(data, size);
  return 0;
}
#endif

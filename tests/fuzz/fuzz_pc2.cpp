// libFuzzer target for the PC2 point-cache reader: read_pc2_header and read_pc2_sample.
//
// Input bytes: a PC2 file, as `simulate --export FILE.pc2` writes it (a 32-byte header
// "POINTCACHE2\0", i32 version, i32 points, f32 start frame, f32 sample rate, i32 samples; then
// float32 x, y, z per point per sample; host/core/io/point_cache.hpp). Each input is read from
// memory: its header, then samples 0, samples / 2 and samples - 1 (those that exist), then the
// samples -1 and `samples`, which must be refused.
//
// Property: read_pc2_header either returns the header's fields bit for bit, with points and
// samples >= 0, a finite start frame and sample rate, and a file of at least 32 + points x
// samples x 12 bytes (more is allowed: a cache being written), or throws clothsim::Pc2Error
// whose message starts with the source name. Each sample read returns `points` points, bit for
// bit the file's floats at 32 + sample x points x 12, all finite; or throws Pc2Error, and then
// the file's floats of that sample hold a NaN or Inf (nothing else can be wrong once the header
// was accepted). No read allocates more than the input's size plus kSlackBytes
// (allocation_meter.hpp). Anything else (another exception, a violated property) calls abort(),
// which libFuzzer reports as a crash; ASan/UBSan reports, hangs (-timeout) and OOMs are crashes
// too.
//
// The same code is built without libFuzzer into clothsim_fuzz_replay (replay_main.cpp), which
// ctest runs over tests/fuzz/seeds_pc2/ and tests/fuzz/regressions/pc2/ in every build.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include <fmt/format.h>

#include "allocation_meter.hpp"
#include "fuzz_targets.hpp"
#include "io/point_cache.hpp"

namespace clothsim::fuzz {
namespace {

// What a read may allocate beyond the input's size: its error message and the exception object.
constexpr uint64_t kSlackBytes = 4096;

[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "fuzz_pc2: PROPERTY VIOLATED: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void expect(bool ok, const std::string& what) {
  if (!ok) violated(what);
}

// One call of a reader on a fresh stream over the input: its value, or its Pc2Error message.
template <class T> struct Read {
  std::optional<T> value;
  std::string error;
};

template <class T, class F> Read<T> read(const std::string& bytes, const char* what, F reader) {
  std::istringstream in(bytes);  // made before the meter starts: its copy is the input's
  Read<T> r;
  try {
    AllocationMeter meter(bytes.size() + kSlackBytes, fmt::format("{} on {} bytes", what, bytes.size()));
    r.value = reader(in);
  } catch (const Pc2Error& e) {
    r.error = e.what();
    expect(r.error.rfind("<fuzz>: ", 0) == 0, "a Pc2Error message does not start with the source: " + r.error);
  } catch (const std::exception& e) {
    violated(fmt::format("an exception other than Pc2Error escaped {}: {}: {}", what, typeid(e).name(), e.what()));
  } catch (...) {
    violated(fmt::format("a non-std exception escaped {}", what));
  }
  return r;
}

template <class T> T get(const std::string& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void check_header(const Pc2Header& h, const std::string& b) {
  expect(b.size() >= 32 && std::memcmp(b.data(), "POINTCACHE2\0", 12) == 0, "loaded without the magic");
  expect(h.version == get<int32_t>(b, 12) && h.points == get<int32_t>(b, 16) &&
             same_bits(h.start_frame, get<float>(b, 20)) && same_bits(h.sample_rate, get<float>(b, 24)) &&
             h.samples == get<int32_t>(b, 28),
         "the header's fields are the file's");
  expect(h.points >= 0 && h.samples >= 0, "points and samples >= 0");
  expect(std::isfinite(h.start_frame) && std::isfinite(h.sample_rate), "start frame and sample rate finite");
  expect(32 + uint64_t(h.points) * uint64_t(h.samples) * 12 <= b.size(), "the file holds every counted sample");
}

// Sample k of a cache whose header `h` was accepted: the file's floats, all finite, or refused
// because they are not.
std::string check_sample(const Pc2Header& h, const std::string& b, int k) {
  const auto r = read<std::vector<glm::vec3>>(b, "read_pc2_sample", [&](std::istream& in) {
    return read_pc2_sample(in, b.size(), "<fuzz>", k);
  });
  const size_t n = size_t(h.points) * 3, at = 32 + size_t(k) * n * 4;
  bool finite = true;
  for (size_t i = 0; i < n; ++i) finite = finite && std::isfinite(get<float>(b, at + 4 * i));
  if (!r.value) {
    expect(!finite, fmt::format("sample {} of an accepted header refused, but its numbers are finite: {}", k, r.error));
    return r.error;
  }
  expect(finite, fmt::format("sample {} holding a NaN or Inf was read", k));
  expect(r.value->size() == size_t(h.points), fmt::format("sample {} has `points` points", k));
  expect(n == 0 || std::memcmp(r.value->data(), b.data() + at, n * 4) == 0, fmt::format("sample {} is the file's", k));
  return "";
}

}  // namespace

Outcome run_pc2(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  Outcome out;
  const auto header = read<Pc2Header>(bytes, "read_pc2_header", [&](std::istream& in) {
    return read_pc2_header(in, bytes.size(), "<fuzz>");
  });
  if (!header.value) {
    out.error = header.error;
    return out;
  }
  const Pc2Header& h = *header.value;
  check_header(h, bytes);
  std::set<int> samples;
  if (h.samples > 0) samples = {0, h.samples / 2, h.samples - 1};
  for (int k : samples) {
    const std::string error = check_sample(h, bytes, k);
    if (out.error.empty()) out.error = error;
  }
  for (int k : {-1, h.samples}) {
    const auto r = read<std::vector<glm::vec3>>(bytes, "read_pc2_sample", [&](std::istream& in) {
      return read_pc2_sample(in, bytes.size(), "<fuzz>", k);
    });
    expect(!r.value, fmt::format("sample {} of a cache of {} was read", k, h.samples));
  }
  out.loaded = out.error.empty();
  return out;
}

}  // namespace clothsim::fuzz

#ifdef CLOTHSIM_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  clothsim::fuzz::run_pc2(data, size);
  return 0;
}
#endif

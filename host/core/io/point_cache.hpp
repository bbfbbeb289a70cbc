// PC2 point caches, the vertex-animation format Blender's Mesh Cache modifier (and 3ds Max,
// Maya, Houdini) reads: a 32-byte header, then float32 x, y, z per point per sample, little
// endian. Written one sample at a time, so memory does not grow with the length of a run.
#pragma once

#include <cstdint>
#include <cstdio>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace clothsim {

struct Pc2Header {
  int32_t version = 1;
  int32_t points = 0;
  float start_frame = 0;  // the frame of sample 0
  float sample_rate = 1;  // frames between samples
  int32_t samples = 0;
};

class Pc2Writer {
 public:
  // Opens `path` and writes a header with no samples; throws std::runtime_error naming the path.
  Pc2Writer(const std::string& path, int points, float start_frame, float sample_rate);
  ~Pc2Writer();
  Pc2Writer(const Pc2Writer&) = delete;
  Pc2Writer& operator=(const Pc2Writer&) = delete;

  // Appends one sample (xyz of each point, rounded to float) and rewrites the header's sample
  // count, so the file is a valid cache of the samples so far whenever the run stops.
  void add(const std::vector<glm::dvec4>& positions);
  void close();  // flushes; throws if anything failed to write
  int samples() const { return header_.samples; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  Pc2Header header_;
  std::vector<float> buffer_;  // one sample, reused
};

// Reading back (tests, and checking a cache before handing it to a DCC tool). The header's
// counts are checked against the file's size before anything is allocated, and its start frame
// and sample rate and every sample read must be finite; a cache that fails either throws
// Pc2Error naming the file.
struct Pc2Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};
Pc2Header read_pc2_header(const std::string& path);
std::vector<glm::vec3> read_pc2_sample(const std::string& path, int sample);
// The same from the `size` bytes of `in` (a file's whole contents, from position 0), for the
// fuzz target (tests/fuzz/fuzz_pc2.cpp); `name` stands for the file in messages.
Pc2Header read_pc2_header(std::istream& in, uint64_t size, const std::string& name);
std::vector<glm::vec3> read_pc2_sample(std::istream& in, uint64_t size, const std::string& name, int sample);

}  // namespace clothsim

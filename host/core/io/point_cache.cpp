#include "io/point_cache.hpp"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <stdexcept>

#include <fmt/format.h>

#include "io/input_file.hpp"

namespace clothsim {
namespace {

static_assert(std::endian::native == std::endian::little, "PC2 is little endian, written in host order");
constexpr char kMagic[12] = "POINTCACHE2";  // with its terminating NUL: 12 bytes
constexpr long kHeaderBytes = 32;
constexpr long kSamplesOffset = 28;  // where the sample count sits in the header

void encode(const Pc2Header& h, uint8_t out[kHeaderBytes]) {
  std::memcpy(out, kMagic, 12);
  std::memcpy(out + 12, &h.version, 4);
  std::memcpy(out + 16, &h.points, 4);
  std::memcpy(out + 20, &h.start_frame, 4);
  std::memcpy(out + 24, &h.sample_rate, 4);
  std::memcpy(out + 28, &h.samples, 4);
}

}  // namespace

Pc2Writer::Pc2Writer(const std::string& path, int points, float start_frame, float sample_rate)
    : path_(path), buffer_(size_t(points) * 3) {
  header_.points = points;
  header_.start_frame = start_frame;
  header_.sample_rate = sample_rate;
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(fmt::format("{}: cannot open for writing ({})", path, std::strerror(errno)));
  uint8_t head[kHeaderBytes];
  encode(header_, head);
  if (std::fwrite(head, 1, sizeof head, file_) != sizeof head) {
    std::fclose(file_);
    file_ = nullptr;
    throw std::runtime_error(fmt::format("{}: write failed", path));
  }
}

Pc2Writer::~Pc2Writer() {
  if (file_) std::fclose(file_);
}

void Pc2Writer::add(const std::vector<glm::dvec4>& pos) {
  if (!file_) throw std::logic_error("Pc2Writer::add after close");
  if (pos.size() != size_t(header_.points))
    throw std::logic_error(fmt::format("{}: a sample of {} points in a cache of {}", path_, pos.size(), header_.points));
  for (size_t i = 0; i < pos.size(); ++i)
    for (int c = 0; c < 3; ++c) buffer_[3 * i + size_t(c)] = float(pos[i][c]);
  ++header_.samples;
  // The seek flushes the sample before the new count is written, so the count on disk never
  // exceeds the samples on disk, even if the process is killed.
  const bool ok = std::fwrite(buffer_.data(), sizeof(float), buffer_.size(), file_) == buffer_.size() &&
                  std::fseek(file_, kSamplesOffset, SEEK_SET) == 0 &&
                  std::fwrite(&header_.samples, 4, 1, file_) == 1 && std::fseek(file_, 0, SEEK_END) == 0;
  if (!ok) throw std::runtime_error(fmt::format("{}: write failed ({})", path_, std::strerror(errno)));
}

void Pc2Writer::close() {
  if (!file_) return;
  const int rc = std::fclose(file_);
  file_ = nullptr;
  if (rc != 0) throw std::runtime_error(fmt::format("{}: write failed", path_));
}

namespace {

// The header, checked against the stream's size before anything is allocated from it: a header
// claiming more points or samples than the file holds (truncated, or corrupted) throws.
Pc2Header read_checked_header(std::istream& in, uint64_t size, const std::string& name) {
  uint8_t head[kHeaderBytes];
  in.seekg(0);
  const bool ok = size >= uint64_t(kHeaderBytes) && in.read(reinterpret_cast<char*>(head), sizeof head);
  if (!ok || std::memcmp(head, kMagic, 12) != 0) throw Pc2Error(fmt::format("{}: not a PC2 file", name));
  Pc2Header h;
  std::memcpy(&h.version, head + 12, 4);
  std::memcpy(&h.points, head + 16, 4);
  std::memcpy(&h.start_frame, head + 20, 4);
  std::memcpy(&h.sample_rate, head + 24, 4);
  std::memcpy(&h.samples, head + 28, 4);
  if (h.points < 0 || h.samples < 0)
    throw Pc2Error(fmt::format("{}: corrupted header ({} points, {} samples)", name, h.points, h.samples));
  // They place the samples on the DCC tool's timeline; a NaN or Inf places them nowhere.
  if (!std::isfinite(h.start_frame) || !std::isfinite(h.sample_rate))
    throw Pc2Error(fmt::format("{}: corrupted header (start frame {}, sample rate {}; expected finite numbers)", name,
                               h.start_frame, h.sample_rate));
  // At most 2^31 x 2^31 x 12 bytes: no overflow in 64 bits. A cache being written may hold
  // part of a sample past the count, so more bytes than needed are fine; fewer are not.
  const uint64_t needed = uint64_t(kHeaderBytes) + uint64_t(h.points) * uint64_t(h.samples) * 12u;
  if (size < needed)
    throw Pc2Error(fmt::format("{}: truncated: the header claims {} points x {} samples ({} bytes), "
                               "the file has {} bytes", name, h.points, h.samples, needed, size));
  return h;
}

// The file's size and an open stream on it.
uint64_t open_for_reading(const std::string& path, std::ifstream& in) {
  // stat first: a FIFO or a device would block the read or never end.
  uint64_t size = 0;
  if (auto problem = input_file_problem(path, &size))
    throw Pc2Error(fmt::format("{}: cannot open: {}", path.empty() ? "\"\"" : printable(path), *problem));
  in.open(path, std::ios::binary);
  if (!in) throw Pc2Error(fmt::format("{}: cannot open", path));
  return size;
}

}  // namespace

Pc2Header read_pc2_header(const std::string& path) {
  std::ifstream in;
  const uint64_t size = open_for_reading(path, in);
  return read_pc2_header(in, size, path);
}

std::vector<glm::vec3> read_pc2_sample(const std::string& path, int sample) {
  std::ifstream in;
  const uint64_t size = open_for_reading(path, in);
  return read_pc2_sample(in, size, path, sample);
}

Pc2Header read_pc2_header(std::istream& in, uint64_t size, const std::string& name) {
  return read_checked_header(in, size, name);
}

std::vector<glm::vec3> read_pc2_sample(std::istream& in, uint64_t size, const std::string& name, int sample) {
  const Pc2Header h = read_checked_header(in, size, name);  // the size covers every counted sample
  if (sample < 0 || sample >= h.samples)
    throw Pc2Error(fmt::format("{}: no sample {} (the cache has {})", name, sample, h.samples));
  std::vector<glm::vec3> out(size_t(h.points));
  const uint64_t offset = uint64_t(kHeaderBytes) + uint64_t(sample) * uint64_t(h.points) * sizeof(glm::vec3);
  in.seekg(std::streamoff(offset));
  if (!in.read(reinterpret_cast<char*>(out.data()), std::streamsize(out.size() * sizeof(glm::vec3))))
    throw Pc2Error(fmt::format("{}: sample {} is truncated", name, sample));
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(out[i][c]))
        throw Pc2Error(fmt::format("{}: sample {}: point {} has {} = {} (a cache holds finite numbers only)", name,
                                   sample, i, "xyz"[c], out[i][c]));
  return out;
}

}  // namespace clothsim

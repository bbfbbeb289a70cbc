#include "export/checkpoint.hpp"

#include "io/input_file.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "io/output_file.hpp"

namespace clothsim {
namespace {

// State file, little endian (README "Checkpoints", docs/export.md):
//   char[16] "clothsim state\n\0", u32 version, u32 scalar bytes, u32 nw, u32 nh, u64 cloth hash,
//   i64 frame, f64 time, u32 scene name length, u32 backend name length, u32 pinned particles,
//   u32 multipliers (version 3; zero before), [version >= 2: f64 dt, the substep length the
//   displacements are per], the two names,
//   positions (nw*nh*4 scalars), displacements (nw*nh*4 scalars), [version 3: the removed xpbd
//   solver's carried multipliers (multipliers*4 scalars; written as none since)], [version 4: the
//   header is 88 bytes, u32 offsets and u32 reserved after dt; after the multipliers the
//   multigrid solve's offsets (offsets*4 scalars; 0 or one per particle)], u64 FNV-1a of all before.
// Version 1 (72-byte header, no dt) is still read: its dt is unknown (SavedState::dt = 0) and
// taken as the loading scene's, i.e. its displacements load unscaled, as they always did.
// A file's multipliers (a state of the removed xpbd solver) are read past and ignored: its
// positions and displacements resume under fabric or classic, which carry none.
static_assert(std::endian::native == std::endian::little, "state files are written in host byte order");
constexpr char kMagic[16] = "clothsim state\n";
constexpr uint32_t kVersion = 4;
constexpr size_t kHeaderBytesV1 = 72, kHeaderBytesV2 = 80, kHeaderBytes = 88;  // by version
constexpr uint32_t kMaxName = 4096;

constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ull, kFnvPrime = 0x100000001b3ull;

void fnv(uint64_t& h, const void* data, size_t n) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * kFnvPrime;
}

template <class T> void put(std::vector<uint8_t>& out, T v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

template <class T> T get(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <class R> std::vector<uint8_t> bytes_of(const std::vector<Vec4<R>>& v) {
  static_assert(sizeof(Vec4<R>) == 4 * sizeof(R));
  std::vector<uint8_t> b(v.size() * sizeof(Vec4<R>));
  if (!b.empty()) std::memcpy(b.data(), v.data(), b.size());
  return b;
}

const char* scalar_name(int bytes) { return bytes == 8 ? "double" : bytes == 4 ? "float" : "unknown"; }

}  // namespace

int pinned_count(const ClothModel& model) {
  int n = 0;
  for (uint8_t p : model.pinned) n += p != 0;
  return n;
}

template <class R> SavedState save_streams(const State<R>& s, int64_t frame, double time, double dt) {
  SavedState out;
  out.scalar_bytes = int(sizeof(R));
  out.frame = frame;
  out.time = time;
  out.dt = dt;
  out.positions = bytes_of(s.pos);
  out.displacement = bytes_of(s.disp);
  if (s.offset.size() == s.pos.size()) out.offsets = bytes_of(s.offset);  // the multigrid solve's
  return out;
}

template <class R> void load_streams(const SavedState& saved, State<R>& s, double dt) {
  // check_fits refuses these for users; this guards callers that skip it.
  if (saved.scalar_bytes != int(sizeof(R)) || saved.particles() != s.pos.size() ||
      saved.displacement.size() != saved.positions.size())
    throw CheckpointError(fmt::format("a state of {} {}-byte particles does not fit a cloth of {} {}-byte particles",
                                      saved.particles(), saved.scalar_bytes, s.pos.size(), sizeof(R)));
  for (size_t i = 0; i < s.pos.size(); ++i) {
    Vec4<R> p;
    std::memcpy(&p, saved.positions.data() + i * sizeof p, sizeof p);
    s.pos[i] = Vec4<R>(p.x, p.y, p.z, s.pos[i].w);
  }
  s.disp.resize(s.pos.size());
  std::memcpy(s.disp.data(), saved.displacement.data(), saved.displacement.size());
  // The multigrid solve's offsets, which fabric's predict reads: as saved, or none (a state of
  // another solver or an older file): the first substep then starts as a fresh run's does.
  s.offset.clear();
  if (saved.offsets.size() == s.pos.size() * sizeof(Vec4<R>)) {
    s.offset.resize(s.pos.size());
    std::memcpy(s.offset.data(), saved.offsets.data(), saved.offsets.size());
  }
  // Saved per substep of another length: the same velocity in this one (as
  // a live edit of the substeps does, with the same function on both backends, so they round
  // alike). Equal lengths, or an unknown one (a version-1 file), leave the bits as they are.
  if (saved.dt > 0 && dt > 0 && saved.dt != dt) rescale_displacement(s, dt / saved.dt);
}

uint64_t cloth_hash(const ClothModel& m) {
  uint64_t h = kFnvOffset;
  const int32_t grid[2] = {m.nw, m.nh};
  fnv(h, grid, sizeof grid);
  fnv(h, m.initial.data(), m.initial.size() * sizeof(glm::dvec3));
  fnv(h, m.pinned.data(), m.pinned.size());
  // A grid's topology follows from nw x nh (and its hash is what it was before meshes); any
  // other model also hashes its triangles and springs, so a state never loads into another mesh.
  if (!m.is_grid()) {
    fnv(h, m.triangles.data(), m.triangles.size() * sizeof(m.triangles[0]));
    for (const Spring& s : m.springs) {
      const uint32_t ends[3] = {s.i, s.j, uint32_t(s.type)};
      fnv(h, ends, sizeof ends);
    }
  }
  return h;
}

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  const SavedState& s = c.state;
  std::vector<uint8_t> head(kMagic, kMagic + sizeof kMagic);
  put<uint32_t>(head, kVersion);
  put<uint32_t>(head, uint32_t(s.scalar_bytes));
  // A mesh (or several cloths) has no grid: its particles are stored as count x 1.
  const bool grid = c.nw > 0 && c.nh > 0;
  put<uint32_t>(head, grid ? uint32_t(c.nw) : uint32_t(s.positions.size() / (4 * size_t(s.scalar_bytes))));
  put<uint32_t>(head, grid ? uint32_t(c.nh) : 1u);
  put<uint64_t>(head, c.cloth);
  put<int64_t>(head, s.frame);
  put<double>(head, s.time);
  put<uint32_t>(head, uint32_t(c.scene.size()));
  put<uint32_t>(head, uint32_t(c.backend.size()));
  put<uint32_t>(head, uint32_t(c.pins));
  put<uint32_t>(head, uint32_t(s.multipliers.size() / (4 * size_t(s.scalar_bytes))));
  put<double>(head, s.dt);
  put<uint32_t>(head, uint32_t(s.offsets.size() / (4 * size_t(s.scalar_bytes))));
  put<uint32_t>(head, 0u);  // reserved
  head.insert(head.end(), c.scene.begin(), c.scene.end());
  head.insert(head.end(), c.backend.begin(), c.backend.end());

  // Under a temporary name beside `path`, renamed once complete (output_file.hpp): an
  // interrupted or failed save leaves the old file.
  PendingFile out(path);
  const std::string& tmp = out.temp();
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw CheckpointError(fmt::format("{}: cannot open for writing ({})", tmp, std::strerror(errno)));
  uint64_t h = kFnvOffset;
  bool ok = true;
  const std::vector<uint8_t>* parts[] = {&head, &s.positions, &s.displacement, &s.multipliers, &s.offsets};
  for (const std::vector<uint8_t>* part : parts) {
    if (part->empty()) continue;  // (no null data() to fwrite: a state without offsets has none)
    fnv(h, part->data(), part->size());
    ok = ok && std::fwrite(part->data(), 1, part->size(), f) == part->size();
  }
  ok = ok && std::fwrite(&h, sizeof h, 1, f) == 1;
  ok = std::fclose(f) == 0 && ok;
  if (!ok) throw CheckpointError(fmt::format("{}: writing the state failed", path));
  try {
    out.commit();
  } catch (const std::runtime_error& e) {
    throw CheckpointError(e.what());
  }
}

Checkpoint read_checkpoint(const std::string& path) {
  // stat first: a FIFO or a device would block the read or never end.
  uint64_t size = 0;
  if (auto problem = input_file_problem(path, &size))
    throw CheckpointError(fmt::format("{}: cannot open the state file: {}", path.empty() ? "\"\"" : printable(path), *problem));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError(fmt::format("{}: cannot open the state file", printable(path)));
  return read_checkpoint(in, size, path);
}

Checkpoint read_checkpoint(std::istream& in, uint64_t size, const std::string& name) {
  auto fail = [&](const std::string& why) { return CheckpointError(fmt::format("{}: {}", name, why)); };
  uint8_t head[kHeaderBytes] = {};
  in.read(reinterpret_cast<char*>(head), std::streamsize(std::min<uintmax_t>(size, kHeaderBytes)));
  if (size < sizeof kMagic || std::memcmp(head, kMagic, sizeof kMagic) != 0)
    throw fail("not a clothsim state file (no 'clothsim state' header)");
  if (size < sizeof kMagic + 4) throw fail(fmt::format("truncated ({} bytes, shorter than the header)", size));
  const uint32_t version = get<uint32_t>(head + 16);
  if (version < 1 || version > kVersion)
    throw fail(fmt::format("state file version {}, this clothsim reads versions 1 to {}", version, kVersion));
  const size_t header = version == 1 ? kHeaderBytesV1 : version <= 3 ? kHeaderBytesV2 : kHeaderBytes;
  if (size < header) throw fail(fmt::format("truncated ({} bytes, shorter than the header)", size));
  in.clear();
  in.seekg(std::streamoff(header));  // a version-1 header is shorter than what was read

  Checkpoint c;
  SavedState& s = c.state;
  const uint32_t scalar = get<uint32_t>(head + 20), nw = get<uint32_t>(head + 24), nh = get<uint32_t>(head + 28);
  const uint32_t scene_len = get<uint32_t>(head + 56), backend_len = get<uint32_t>(head + 60);
  if (scalar != 4 && scalar != 8) throw fail(fmt::format("scalar size {} bytes (expected 4 or 8)", scalar));
  if (nw < 1 || nh < 1 || uint64_t(nw) * nh < 3 || uint64_t(nw) * nh > uint64_t(kMaxParticles))
    throw fail(fmt::format("grid {}x{} is out of range", nw, nh));
  if (scene_len > kMaxName || backend_len > kMaxName) throw fail("corrupted header (name lengths out of range)");
  const uint64_t stream = uint64_t(nw) * nh * 4 * scalar;
  const uint32_t multipliers = version >= 3 ? get<uint32_t>(head + 68) : 0;
  // At most 64 springs per particle (more than any cloth model has), so the size below is bounded.
  if (uint64_t(multipliers) > 64 * uint64_t(nw) * nh)
    throw fail(fmt::format("{} spring multipliers for {} particles is out of range", multipliers, uint64_t(nw) * nh));
  const uint64_t multiplier_stream = uint64_t(multipliers) * 4 * scalar;
  const uint32_t offsets = version >= 4 ? get<uint32_t>(head + 80) : 0;
  if (offsets != 0 && uint64_t(offsets) != uint64_t(nw) * nh)
    throw fail(fmt::format("{} solve offsets for {} particles (expected 0 or one per particle)", offsets, uint64_t(nw) * nh));
  const uint64_t offset_stream = uint64_t(offsets) * 4 * scalar;
  const uint64_t expected =
      header + scene_len + backend_len + 2 * stream + multiplier_stream + offset_stream + sizeof(uint64_t);
  if (size != expected)
    throw fail(fmt::format("{} ({} bytes, a {}x{} cloth of {}-byte scalars needs {})",
                           size < expected ? "truncated" : "has trailing bytes", size, nw, nh, scalar, expected));
  s.scalar_bytes = int(scalar);
  c.nw = int(nw);
  c.nh = int(nh);
  c.cloth = get<uint64_t>(head + 32);
  c.pins = int(get<uint32_t>(head + 64));
  s.frame = get<int64_t>(head + 40);
  s.time = get<double>(head + 48);
  s.dt = version == 1 ? 0.0 : get<double>(head + 72);
  c.version = int(version);
  // Every size is checked against the file's above, so nothing below allocates more than it holds.
  c.scene.resize(scene_len);
  c.backend.resize(backend_len);
  s.positions.resize(stream);
  s.displacement.resize(stream);
  s.multipliers.resize(multiplier_stream);
  s.offsets.resize(offset_stream);
  uint64_t stored = 0;
  in.read(c.scene.data(), scene_len);
  in.read(c.backend.data(), backend_len);
  in.read(reinterpret_cast<char*>(s.positions.data()), std::streamsize(stream));
  in.read(reinterpret_cast<char*>(s.displacement.data()), std::streamsize(stream));
  in.read(reinterpret_cast<char*>(s.multipliers.data()), std::streamsize(multiplier_stream));
  in.read(reinterpret_cast<char*>(s.offsets.data()), std::streamsize(offset_stream));
  in.read(reinterpret_cast<char*>(&stored), sizeof stored);
  if (!in) throw fail("read failed");
  uint64_t h = kFnvOffset;
  fnv(h, head, header);
  fnv(h, c.scene.data(), scene_len);
  fnv(h, c.backend.data(), backend_len);
  fnv(h, s.positions.data(), stream);
  fnv(h, s.displacement.data(), stream);
  fnv(h, s.multipliers.data(), multiplier_stream);
  fnv(h, s.offsets.data(), offset_stream);
  if (h != stored) throw fail("corrupted (checksum mismatch)");
  // A state that passed its checksum may still hold what no run can continue from (written
  // by hand, or by a foreign tool): every number is checked before a backend sees it.
  if (!std::isfinite(s.time) || s.time < 0) throw fail(fmt::format("the simulated time is {} (expected a finite time >= 0)", s.time));
  if (s.frame < 0) throw fail(fmt::format("the frame is {} (expected >= 0)", s.frame));
  if (version != 1 && !(std::isfinite(s.dt) && s.dt > 0))
    throw fail(fmt::format("the substep length is {} s (expected a finite length > 0)", s.dt));
  const char* streams[4] = {"position", "displacement", "multiplier", "solve offset"};
  const char* owners[4] = {"particle", "particle", "spring", "particle"};
  const std::vector<uint8_t>* stream_bytes[4] = {&s.positions, &s.displacement, &s.multipliers, &s.offsets};
  for (int k = 0; k < 4; ++k) {
    const std::vector<uint8_t>& bytes = *stream_bytes[k];
    const size_t n = bytes.size() / scalar;
    for (size_t i = 0; i < n; ++i) {
      const double v = scalar == 8 ? get<double>(bytes.data() + 8 * i) : double(get<float>(bytes.data() + 4 * i));
      if (!std::isfinite(v))
        throw fail(fmt::format("the {} of {} {} has {} = {} (a state holds finite numbers only)", streams[k],
                               owners[k], i / 4, "xyzw"[i % 4], v));
    }
  }
  return c;
}

void check_fits(const Checkpoint& c, const std::string& path, const Scene& scene, const ClothModel& model,
                int scalar_bytes, const std::string& backend) {
  const uint64_t here = cloth_hash(model);
  if (c.cloth != here)
    throw CheckpointError(fmt::format(
        "{}: a different cloth: the state was saved from a {}x{} cloth with {} pinned particles (scene {}, cloth "
        "hash {:016x}), but scene {} has a {}x{} cloth with {} (cloth hash {:016x}). A state loads only into the "
        "cloth it was saved from: same grid, width, height, orientation and pins (other parameters may change)",
        path, c.nw, c.nh, c.pins, printable(c.scene), c.cloth, scene.source, model.nw, model.nh, pinned_count(model), here));
  if (c.state.scalar_bytes != scalar_bytes)
    throw CheckpointError(fmt::format(
        "{}: the state holds {}-byte ({}) scalars, saved by backend {}, but backend {} runs in {}-byte ({}). "
        "States are kept bit for bit, so they load only into a backend of the same precision",
        path, c.state.scalar_bytes, scalar_name(c.state.scalar_bytes), printable(c.backend), backend, scalar_bytes,
        scalar_name(scalar_bytes)));
}

#define CLOTHSIM_INSTANTIATE(R)                                                  \
  template SavedState save_streams<R>(const State<R>&, int64_t, double, double); \
  template void load_streams<R>(const SavedState&, State<R>&, double);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

#include "export/frame_export.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "io/output_file.hpp"

namespace clothsim {
namespace fs = std::filesystem;
namespace {

bool ends_with_pc2(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  std::string lower;
  for (char c : ext) lower += char(std::tolower(static_cast<unsigned char>(c)));
  return lower == ".pc2";
}

// Whether two OBJ files hold the same mesh: the same lines and words, numbers equal to 1e-6
// (relative, or absolute below 1), so the start state of a float run matches that of a double
// one. Normals (vn) are not compared: they follow from the vertices (and the backends' start
// states differ there). Any other difference in vertex count, positions, uv or triangles is
// a different mesh.
bool same_mesh(const std::string& a, const std::string& b) {
  std::ifstream fa(a), fb(b);
  if (!fa || !fb) return false;
  auto next_line = [](std::ifstream& in, std::string& line) {
    while (std::getline(in, line))
      if (line.rfind("vn ", 0) != 0) return true;
    return false;
  };
  auto same_number = [](const std::string& x, const std::string& y) {
    char *end_x = nullptr, *end_y = nullptr;
    const double u = std::strtod(x.c_str(), &end_x), v = std::strtod(y.c_str(), &end_y);
    return !*end_x && !*end_y && end_x != x.c_str() && end_y != y.c_str() && std::isfinite(u) && std::isfinite(v) &&
           std::abs(u - v) <= 1e-6 * std::max({1.0, std::abs(u), std::abs(v)});
  };
  std::string la, lb;
  while (true) {
    const bool more_a = next_line(fa, la), more_b = next_line(fb, lb);
    if (more_a != more_b) return false;
    if (!more_a) return true;
    if (la == lb) continue;
    std::istringstream wa(la), wb(lb);
    std::string x, y;
    while (true) {
      const bool word_a = bool(wa >> x), word_b = bool(wb >> y);
      if (word_a != word_b) return false;
      if (!word_a) break;
      if (x != y && !same_number(x, y)) return false;
    }
  }
}

// The rule for the PC2 (docs/export.md): the cache is streamed into a temporary beside PATH
// (created exclusively under an unguessable name, output_file.hpp) and renamed over PATH only
// when the run ends successfully (finish()), removing a PATH.partial an earlier run left. A run
// that stops early (a divergence: finish_incomplete(); any other failure: the destructor)
// leaves PATH as it was and renames the temporary to PATH.partial, a valid cache of the frames
// written so far, saying so; a cache whose writing failed (a full disk) is removed, since its
// last sample may be missing. PATH.partial is clothsim's own name: a run replaces the one an
// earlier run left (the name itself: a symlink there is replaced, never followed), and the
// output checks refuse a PATH.partial that is not a regular file before the run.
//
// The mesh beside it (FILE.obj for FILE.pc2) is written at the start, the start state. The
// user named only the cache, so an existing FILE.obj is replaced by nothing: if it already
// holds this mesh (same_mesh) it is left as it is, otherwise the export is refused before the
// run, naming the file. A mesh named with --export-mesh is the user's to replace.
class PointCacheExport final : public FrameExport {
 public:
  PointCacheExport(const std::string& path, const ClothModel& model, int64_t start, int every, const ClothSnapshot& s,
                   const std::string& mesh_path)
      : FrameExport(start, every), path_(path), partial_(partial_cache_path(path)),
        mesh_(mesh_path.empty() ? mesh_beside_cache(path) : mesh_path),
        points_(model.count()) {
    std::error_code ec;
    existed_ = fs::exists(path_, ec);
    // The mesh Blender imports and the cache deforms: same vertex order, uv and triangles.
    if (!mesh_path.empty() || !fs::exists(mesh_, ec)) {
      write_obj(mesh_, model, s);
    } else {
      PendingFile fresh(mesh_);
      write_obj(fresh.temp(), model, s);
      if (!same_mesh(fresh.temp(), mesh_))
        throw std::runtime_error(fmt::format(
            "{}: the mesh written beside the cache, {}, exists and holds another mesh; it is not overwritten, "
            "since it was not named: remove it, or name where the mesh goes with --export-mesh FILE.obj",
            path, mesh_));
      mesh_kept_ = true;  // already this mesh: left as it is
    }
    cache_.emplace(path_);
    pc2_.emplace(cache_->temp(), model.count(), float(start), float(every));
    state_ = State::Writing;
    add(start, s);
  }
  ~PointCacheExport() override {
    if (state_ != State::Writing) return;
    // Stopped by an exception (not a divergence, not a write error): keep what was written.
    try {
      keep_partial();
      fmt::print(stderr, "{}\n", kept_sentence("the run stopped"));
    } catch (...) {
    }
  }
  void add(int64_t, const ClothSnapshot& s) override {
    try {
      pc2_->add(s.pos);
    } catch (const std::runtime_error& e) {
      // A write failed: the partial cache cannot be trusted (nor, likely, the disk's space).
      drop();
      throw std::runtime_error(fmt::format("{}; removed the partial cache, {} is {}", e.what(), path_,
                                           existed_ ? "unchanged" : "not written"));
    }
    ++written_;
  }
  void finish() override {
    try {
      pc2_->close();
      cache_->commit();
    } catch (const std::runtime_error&) {
      drop();
      throw;
    }
    state_ = State::Done;
    // A partial an earlier run left is stale now (a regular file only: checked before the run).
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(partial_, ec))) remove_quietly(partial_);
  }
  std::string finish_incomplete(const std::string& why) override {
    keep_partial();
    return kept_sentence(why);
  }
  std::string summary() const override {
    return fmt::format("{} ({} sample{} of {} points, one every {} frame{}) and the mesh {}{}",
                       state_ == State::Done ? path_ : partial_, samples(), samples() == 1 ? "" : "s", points_, every_,
                       every_ == 1 ? "" : "s", mesh_, mesh_kept_ ? " (already this mesh, left as it was)" : "");
  }

 private:
  enum class State { Opening, Writing, Kept, Done, Removed };
  int samples() const { return samples_ >= 0 ? samples_ : pc2_ ? pc2_->samples() : 0; }
  // Closes the cache and renames it to PATH.partial; a failure removes it and passes on.
  void keep_partial() {
    try {
      samples_ = pc2_->samples();
      pc2_->close();
      cache_->commit_as(partial_);
    } catch (const std::runtime_error&) {
      drop();
      throw;
    }
    state_ = State::Kept;
  }
  void drop() {
    samples_ = pc2_ ? pc2_->samples() : 0;
    pc2_.reset();
    if (cache_) cache_->discard();
    state_ = State::Removed;
  }
  std::string kept_sentence(const std::string& why) const {
    return fmt::format("kept {} ({} sample{}, the frames before {}; a valid cache, rename it to use it); {} is {}",
                       partial_, samples(), samples() == 1 ? "" : "s", why, path_,
                       existed_ ? "unchanged" : "not written");
  }
  std::string path_, partial_, mesh_;
  std::optional<PendingFile> cache_;  // the temporary the cache streams into
  std::optional<Pc2Writer> pc2_;
  int points_, samples_ = -1;
  bool existed_ = false, mesh_kept_ = false;
  State state_ = State::Opening;
};

class ObjSequenceExport final : public FrameExport {
 public:
  ObjSequenceExport(const std::string& dir, const ClothModel& model, int64_t start, int every, const ClothSnapshot& s)
      : FrameExport(start, every), dir_(dir), model_(model) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec || !fs::is_directory(dir_))
      throw std::runtime_error(fmt::format("{}: cannot create the directory ({})", dir, ec.message()));
    add(start, s);
  }
  void add(int64_t frame, const ClothSnapshot& s) override {
    last_ = (dir_ / fmt::format("frame_{:04d}.obj", frame)).string();
    write_obj(last_, model_, s);
    if (written_++ == 0) first_ = last_;
  }
  void finish() override {}
  std::string finish_incomplete(const std::string& why) override {
    return fmt::format("wrote {} (the frames before {})", summary(), why);
  }
  std::string summary() const override {
    return written_ == 1 ? first_ : fmt::format("{} OBJs, {} ... {}", written_, first_, last_);
  }

 private:
  fs::path dir_;
  const ClothModel& model_;
  std::string first_, last_;
};

}  // namespace

std::string mesh_beside_cache(const std::string& pc2) { return fs::path(pc2).replace_extension(".obj").string(); }

ExportKind export_kind(const std::string& path) {
  if (path.empty()) return ExportKind::None;
  if (ends_with_pc2(path)) return ExportKind::PointCache;
  std::error_code ec;
  if (path.back() == '/' || fs::is_directory(path, ec)) return ExportKind::ObjSequence;
  return ExportKind::Obj;
}

std::unique_ptr<FrameExport> open_frame_export(ExportKind kind, const std::string& path, const ClothModel& model,
                                               int64_t start_frame, int every, const ClothSnapshot& start,
                                               const std::string& mesh_path) {
  if (every < 1) throw std::invalid_argument("open_frame_export: every must be at least 1");
  if (kind == ExportKind::PointCache) return std::make_unique<PointCacheExport>(path, model, start_frame, every, start, mesh_path);
  if (kind == ExportKind::ObjSequence) return std::make_unique<ObjSequenceExport>(path, model, start_frame, every, start);
  throw std::invalid_argument("open_frame_export: not a sequence export");
}

}  // namespace clothsim

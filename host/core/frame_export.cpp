#include "frame_export.hpp"

#include <cctype>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

namespace clothsim {
namespace fs = std::filesystem;
namespace {

bool ends_with_pc2(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  std::string lower;
  for (char c : ext) lower += char(std::tolower(static_cast<unsigned char>(c)));
  return lower == ".pc2";
}

class PointCacheExport final : public FrameExport {
 public:
  PointCacheExport(const std::string& path, const ClothModel& model, int64_t start, int every, const ClothSnapshot& s)
      : FrameExport(start, every), mesh_(fs::path(path).replace_extension(".obj").string()),
        pc2_(path, model.count(), float(start), float(every)), points_(model.count()) {
    // The mesh Blender imports and the cache deforms: same vertex order, uv and triangles.
    write_obj(mesh_, model, s);
    add(start, s);
  }
  void add(int64_t, const ClothSnapshot& s) override {
    pc2_.add(s.pos);
    ++written_;
  }
  void finish() override { pc2_.close(); }
  std::string summary() const override {
    return fmt::format("{} ({} sample{} of {} points, one every {} frame{}) and the mesh {}", pc2_.path(),
                       pc2_.samples(), pc2_.samples() == 1 ? "" : "s", points_, every_, every_ == 1 ? "" : "s", mesh_);
  }

 private:
  std::string mesh_;
  Pc2Writer pc2_;
  int points_;
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
  std::string summary() const override {
    return written_ == 1 ? first_ : fmt::format("{} OBJs, {} ... {}", written_, first_, last_);
  }

 private:
  fs::path dir_;
  const ClothModel& model_;
  std::string first_, last_;
};

}  // namespace

ExportKind export_kind(const std::string& path) {
  if (path.empty()) return ExportKind::None;
  if (ends_with_pc2(path)) return ExportKind::PointCache;
  std::error_code ec;
  if (path.back() == '/' || fs::is_directory(path, ec)) return ExportKind::ObjSequence;
  return ExportKind::Obj;
}

std::unique_ptr<FrameExport> open_frame_export(ExportKind kind, const std::string& path, const ClothModel& model,
                                               int64_t start_frame, int every, const ClothSnapshot& start) {
  if (every < 1) throw std::invalid_argument("open_frame_export: every must be at least 1");
  if (kind == ExportKind::PointCache) return std::make_unique<PointCacheExport>(path, model, start_frame, every, start);
  if (kind == ExportKind::ObjSequence) return std::make_unique<ObjSequenceExport>(path, model, start_frame, every, start);
  throw std::invalid_argument("open_frame_export: not a sequence export");
}

}  // namespace clothsim

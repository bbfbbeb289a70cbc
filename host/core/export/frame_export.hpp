// `simulate --export` of the whole motion: a PC2 point cache (+ the mesh as OBJ beside it) or
// a directory of OBJs, one per exported frame, each frame written as soon as it is computed,
// so memory stays that of one frame however long the run.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "cloth/cloth.hpp"
#include "analysis/diagnostics.hpp"
#include "io/point_cache.hpp"

namespace clothsim {

enum class ExportKind {
  None,
  Obj,          // FILE.obj (or any other name): the last frame only
  PointCache,   // FILE.pc2: every K-th frame, plus FILE.obj (or --export-mesh) with the mesh
  ObjSequence,  // DIR/ (a trailing slash, or an existing directory): DIR/frame_NNNN.obj
};
ExportKind export_kind(const std::string& path);
// Where a PC2 export keeps the frames of a run that stopped early: PATH.partial.
inline std::string partial_cache_path(const std::string& pc2) { return pc2 + ".partial"; }
// The mesh a PC2 export writes beside it when no --export-mesh names one: FILE.obj.
std::string mesh_beside_cache(const std::string& pc2);

class FrameExport {
 public:
  virtual ~FrameExport() = default;
  // Whether `frame` is one to write: the start frame and every `every`-th frame after it.
  bool wants(int64_t frame) const { return frame >= start_ && (frame - start_) % every_ == 0; }
  virtual void add(int64_t frame, const ClothSnapshot& s) = 0;
  // The run ended successfully: flushes and closes (a PC2 is renamed from its temporary over
  // PATH); afterwards summary() says what was written.
  virtual void finish() = 0;
  // The run stopped early (`why`: "the divergence"): closes what was written and returns the
  // sentence saying where it is (a PC2 is kept as PATH.partial; PATH is left as it was).
  virtual std::string finish_incomplete(const std::string& why) = 0;
  virtual std::string summary() const = 0;
  int written() const { return written_; }

 protected:
  FrameExport(int64_t start, int every) : start_(start), every_(every) {}
  int64_t start_;
  int every_;
  int written_ = 0;
};

// Opens the export and writes `start` (frame `start_frame`, the state the run begins from).
// Throws std::runtime_error naming the path when it cannot be written, or, for a PC2, when the
// mesh beside it (`mesh_path`, empty: FILE.obj beside FILE.pc2, which is then written only if
// absent or already this mesh) cannot be. The rules: frame_export.cpp, docs/export.md.
std::unique_ptr<FrameExport> open_frame_export(ExportKind kind, const std::string& path, const ClothModel& model,
                                               int64_t start_frame, int every, const ClothSnapshot& start,
                                               const std::string& mesh_path = {});

}  // namespace clothsim

// --export-colliders DIR/ (docs/export.md, "Colliders"): every mesh collider of the scene as it
// stands at each exported frame, DIR/mesh0/frame_NNNN.obj, DIR/mesh1/..., in scene coordinates
// and numbered like --export DIR/'s frames, so that a cloth's point cache and the bodies it
// drapes over play back together in Blender or any tool that reads OBJ sequences; and, at the
// end of the run, each collider's frames as one point cache, DIR/meshK/mesh.pc2.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "colliders/mesh_collider.hpp"
#include "io/output_file.hpp"
#include "io/point_cache.hpp"

namespace clothsim {

class OutputPlan;

// The folder of mesh collider k in `dir` ("DIR/mesh0").
std::string collider_folder(const std::string& dir, size_t k);

// Adds the files the export will write to `plan`: frames start, start + every, ... up to
// start + frames, in each mesh collider's folder.
void plan_collider_export(OutputPlan& plan, const Scene& scene, const std::string& dir, int64_t start, int frames,
                          int every);

class ColliderExport {
 public:
  // Loads the scene's mesh colliders (already built for the run: shared) and creates the
  // folders. Throws std::runtime_error naming a folder that cannot be created.
  ColliderExport(const Scene& scene, const std::string& dir, int64_t start, int every);
  bool wants(int64_t frame) const { return frame >= start_ && (frame - start_) % every_ == 0; }
  // Writes every collider at simulated time `time` (s) as frame `frame`.
  void add(int64_t frame, double time);
  // After the last frame of a run that ended well: every collider's frames as one point cache,
  // DIR/meshK/mesh.pc2 over the first frame's OBJ (Blender's Mesh Cache plays it), one sample
  // per exported frame, streamed into a temporary beside it as the frames come and renamed over
  // it here (a run that stops early leaves no cache). Throws std::runtime_error naming a file
  // that cannot be written.
  void finish();
  std::string summary() const;

 private:
  const Scene& scene_;
  std::string dir_;
  int64_t start_;
  int every_;
  std::vector<std::shared_ptr<const ColliderMesh>> meshes_;
  // Per collider, the cache's temporary and its writer (destroyed first: closed, then removed
  // unless finish() renamed it).
  std::vector<std::unique_ptr<PendingFile>> caches_;
  std::vector<std::unique_ptr<Pc2Writer>> writers_;
  int written_ = 0;
  bool cached_ = false;
  int64_t first_ = 0, last_ = 0;
};

}  // namespace clothsim

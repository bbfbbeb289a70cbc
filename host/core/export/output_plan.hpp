// Every file a run will write, checked before the run starts (docs/export.md, "Before the
// run"): each output must be a regular file or absent (a FIFO, a device, a socket, a directory
// or a symlink to one is never replaced), its folder must exist and be writable, no two outputs
// may name the same file (companions counted: the OBJ beside a PC2, its .partial, the frames of
// a sequence folder), and no output may name a file the run reads (scene, meshes, textures,
// state). A failed check throws OutputError, which the commands end with exit code 2.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace clothsim {

struct Scene;

struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `p` without its trailing slashes ("out//" is "out"; "/" stays "/").
inline std::string strip_slashes(std::string p) {
  while (p.size() > 1 && p.back() == '/') p.pop_back();
  return p;
}

class OutputPlan {
 public:
  // A file the run reads (`what`: "the scene", "--load-state", "mesh[0].file", ...).
  void input(const std::string& what, const std::string& path);
  // The scene's file and every file it names (cloth meshes, collider meshes).
  void inputs_of(const Scene& scene);
  // Every regular file directly in `folder` (the renderer's textures and shaders).
  void inputs_in(const std::string& what, const std::string& folder);

  // A file the user named with `flag`.
  void file(const std::string& flag, const std::string& path);
  // A file written because `flag` named another (`why`: "the mesh written beside --export
  // run.pc2", said after the path in messages).
  void companion(const std::string& flag, const std::string& path, const std::string& why);
  // A folder `flag` names, and the names of the files the run writes into it.
  void folder(const std::string& flag, const std::string& path, const std::vector<std::string>& names);

  // Throws OutputError naming the flag, the path and the problem.
  void check() const;

 private:
  struct Output {
    std::string flag, path, why;  // why: empty for a file the user named
    std::string folder;           // for a file of a sequence folder: the folder
  };
  struct Input {
    std::string what, path;
  };
  std::vector<Output> outputs_;
  std::vector<std::string> folders_;  // as given, for their own checks
  std::vector<std::string> folder_flags_;
  std::vector<Input> inputs_;
};

}  // namespace clothsim

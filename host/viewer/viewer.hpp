// The interactive viewer: a GLFW window that simulates on the GPU and draws from the same
// buffers, with the classic keys and mouse and Dear ImGui panels.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace clothsim {

struct ViewerOptions {
  std::filesystem::path root;      // project root (shaders/, compute/, textures/)
  std::string scene_path;          // empty: the built-in pinned2
  std::vector<std::string> sets;   // --set overrides
  int sphere_lat = 40, sphere_lon = 40;
  int frames = -1;                 // scripted mode: run this many frames unpaused...
  std::string screenshot;          // ...then save the window here and exit
  int width = 1280, height = 800;
};

// Returns the process exit code (3 when no window can be opened).
int run_viewer(const ViewerOptions& options);

}  // namespace clothsim

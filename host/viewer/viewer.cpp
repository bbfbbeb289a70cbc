#include "viewer.hpp"

#include <fmt/format.h>

#include "viewer_app.hpp"

namespace clothsim {

int run_viewer(const ViewerOptions& o) {
  // The scene first: a bad file is exit 2 whether or not a window can be opened.
  Scene scene;
  try {
    scene = o.scene_path.empty() ? default_scene(o.sets) : load_scene(o.scene_path, o.sets);
  } catch (const SceneError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  std::string why;
  auto window = GlfwWindow::create("clothsim", o.width, o.height, true, &why);
  if (!window) {
    fmt::print(stderr,
               "error: {}\n  The viewer needs a display and an OpenGL 4.3 driver. Without a display, render "
               "headless instead, e.g.\n    clothsim render scenes/pinned2.json --frames 90 --out pinned2.mp4\n",
               why);
    return 3;
  }
  if (const std::string notice = gl::software_renderer_notice(); !notice.empty()) fmt::print(stderr, "{}\n", notice);
  Viewer viewer(o, std::move(window));
  viewer.load(scene);
  return viewer.run();
}

}  // namespace clothsim

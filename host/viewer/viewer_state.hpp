// Everything the viewer's panels read and change, apart from GL objects.
#pragma once

#include <deque>
#include <memory>
#include <string>

#include "camera.hpp"
#include "picking.hpp"
#include "renderer.hpp"
#include "scene/scene.hpp"

namespace clothsim {

struct ViewerStats {
  double fps = 0, sim_ms = 0, render_ms = 0;
  bool gpu_timers = false;  // GL timer queries (else CPU clock around glFinish)
  RenderTimes passes;       // the renderer's passes of the last frame
  int dispatches_per_frame = 0;
  int particles = 0, springs = 0;
  int contacts = -1;        // self-collision contacts (refreshed twice a second)
};

struct ViewerState {
  Scene scene;               // what the panels edit
  Appearance look;
  OrbitCamera camera;
  bool paused = true;        // the classic viewer starts paused
  bool step_once = false;
  bool show_panels = true;
  ViewerStats stats;
  std::string status;        // last message for the user (saved, loaded, errors)
  std::string divergence;    // why the simulation stopped (divergence_message); empty while it runs
  std::string path_field;    // Scene panel's file path
  // Requests from the panels, handled by the main loop.
  bool parameters_changed = false;
  bool reload_requested = false;
  std::string open_requested;
};

// Draws the four panels (Simulation, Appearance, Scene, Stats) with ImGui.
void draw_panels(ViewerState& state, const std::filesystem::path& root);

}  // namespace clothsim

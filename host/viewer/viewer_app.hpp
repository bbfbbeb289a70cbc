// The viewer application object: window, ImGui, the loaded scene's simulator and renderer,
// and the main loop. Input handling lives in viewer_input.cpp.
#pragma once

#include "viewer.hpp"
#include <algorithm>
#include <chrono>
#include <memory>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include "contacts.hpp"
#include "context.hpp"
#include "io/output_file.hpp"
#include "glfw_window.hpp"
#include "gpu_simulator.hpp"
#include "png.hpp"
#include "viewer_state.hpp"

namespace clothsim {


// The GL side of one loaded scene; rebuilt when another scene is opened.
struct Session {
  std::unique_ptr<ClothModel> model;
  std::unique_ptr<GpuSimulator> sim;
  std::unique_ptr<Renderer> renderer;
};

class Viewer {
 public:
  Viewer(const ViewerOptions& o, std::unique_ptr<GlfwWindow> w) : opts_(o), window_(std::move(w)) {
    glfwSetWindowUserPointer(window_->handle(), this);
    install_callbacks();
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the user's directory
    ImGui_ImplGlfw_InitForOpenGL(window_->handle(), true);  // chains to our callbacks
    ImGui_ImplOpenGL3_Init("#version 430 core");
  }
  ~Viewer() {
    session_ = {};
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }

  void load(const Scene& scene) {
    session_ = {};
    st_.scene = scene;
    session_.model = std::make_unique<ClothModel>(build_cloth(scene));
    session_.sim = std::make_unique<GpuSimulator>(scene, *session_.model, opts_.root / "compute");
    session_.renderer = std::make_unique<Renderer>(opts_.root, scene, *session_.model,
                                                   RendererOptions{opts_.sphere_lat, opts_.sphere_lon});
    session_.renderer->set_timing(true);  // the Stats panel shows every pass
    reset_camera();
    st_.divergence.clear();
    st_.stats.particles = session_.model->count();
    st_.stats.springs = int(session_.model->springs.size());
    if (st_.path_field.empty()) st_.path_field = scene.source;
    glfwSetWindowTitle(window_->handle(), fmt::format("clothsim - {}", scene.name()).c_str());
  }

  int run() {
    if (opts_.frames >= 0) st_.paused = false;  // scripted mode runs unpaused
    int frames_done = 0, frames_to_exit = 0;
    auto last = std::chrono::steady_clock::now();
    while (!glfwWindowShouldClose(window_->handle())) {
      glfwPollEvents();
      handle_requests();
      if (!st_.paused || st_.step_once) {
        if (grab_.active()) session_.sim->hold_particle(grab_.particle, grab_target_);
        sim_timer_.mark(0);
        session_.sim->step_frame();
        sim_timer_.mark(1);
        st_.stats.sim_ms = sim_timer_.finish()[0];
        st_.step_once = false;
        ++frames_done;
      }
      // Scripted mode cannot wait for a key after a divergence: it draws a few more (paused)
      // frames, so ImGui has laid out the panel with the message, saves the screenshot, exits 1.
      if (poll_divergence() && opts_.frames >= 0) frames_to_exit = 3;
      const bool diverged = frames_to_exit > 0;
      const bool last_frame = opts_.frames >= 0 && (diverged ? --frames_to_exit == 0 : frames_done >= opts_.frames);
      draw();
      if (last_frame) {
        if (diverged) fmt::print(stderr, "error: {}\n", st_.divergence);
        return save_screenshot(opts_.screenshot) && !diverged ? 0 : 1;
      }
      glfwSwapBuffers(window_->handle());
      const auto now = std::chrono::steady_clock::now();
      const double dt = std::chrono::duration<double>(now - last).count();
      last = now;
      st_.stats.fps = 0.9 * st_.stats.fps + 0.1 * (dt > 0 ? 1.0 / dt : 0.0);
      refresh_contacts();
    }
    return 0;
  }

 private:
  void draw() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_->handle(), &w, &h);
    st_.camera.aspect = h > 0 ? float(w) / float(h) : 1.f;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    render_timer_.mark(0);
    // Keyframed (or alt-dragged) colliders are drawn where the simulation has them now.
    session_.renderer->place_colliders(session_.sim->constants());
    session_.renderer->draw(session_.sim->state().positions(), session_.sim->state().normals(), st_.camera, st_.look);
    render_timer_.mark(1);
    st_.stats.render_ms = render_timer_.finish()[0];
    st_.stats.passes = session_.renderer->times();
    st_.stats.gpu_timers = sim_timer_.uses_queries();
    st_.stats.dispatches_per_frame = session_.sim->passes().dispatches_per_substep() * st_.scene.simulation.simulation_steps +
                                     1 + GpuDivergenceGuard::kDispatchesPerFrame;  // normals, the guard
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (st_.show_panels) draw_panels(st_, opts_.root);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  void handle_requests() {
    if (st_.parameters_changed) {
      session_.sim->set_parameters(st_.scene);
      st_.parameters_changed = false;
    }
    std::string path = std::exchange(st_.open_requested, "");
    if (st_.reload_requested) path = st_.scene.source;
    st_.reload_requested = false;
    if (path.empty()) return;
    try {
      const bool diverged = !st_.divergence.empty();
      load(path[0] == '<' ? default_scene(opts_.sets) : load_scene(path, opts_.sets));
      if (diverged) st_.paused = false;  // a reload after a divergence starts running again
      st_.status = fmt::format("loaded {}", path);
    } catch (const std::exception& e) {
      st_.status = e.what();  // a bad file is reported in the panel; the current scene stays
    }
  }

  void refresh_contacts() {
    const auto now = std::chrono::steady_clock::now();
    if (!st_.show_panels || now - last_contacts_ < std::chrono::milliseconds(500)) return;
    last_contacts_ = now;
    st_.stats.contacts = -1;
    if (!st_.scene.simulation.self_collision) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    st_.stats.contacts =
        count_self_contacts(gl::download_vector<glm::vec4>(session_.sim->state().positions()), session_.sim->constants());
  }

  bool save_screenshot(const std::string& path) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_->handle(), &w, &h);
    std::vector<uint8_t> rows(size_t(w) * h * 4), flipped(rows.size());
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    for (int y = 0; y < h; ++y)
      std::copy_n(rows.data() + size_t(h - 1 - y) * w * 4, size_t(w) * 4, flipped.data() + size_t(y) * w * 4);
    for (size_t i = 3; i < flipped.size(); i += 4) flipped[i] = 255;  // an opaque image whatever the alpha
    try {
      // Beside `path` first, renamed once complete: an old screenshot is never left half written.
      write_replacing(path, [&](const std::string& temp) {
        try {
          write_png_file(temp, w, h, flipped);
        } catch (const std::exception&) {
          throw std::runtime_error(fmt::format("{}: cannot write the PNG", path));
        }
      });
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return false;
    }
    fmt::print("wrote {} ({}x{})\n", path, w, h);
    st_.status = fmt::format("wrote {}", path);
    return true;
  }

  void reset_camera() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_->handle(), &w, &h);
    st_.camera = default_camera(st_.scene, *session_.model, h > 0 ? float(w) / float(h) : 1.f);
  }

  // The divergence guard's results (viewer_divergence.cpp): a failed frame pauses the viewer
  // on the newest frame that passed, with the message in the panel. True on a new failure.
  bool poll_divergence();
  // After a failure, P, N, R, reload and open clear the message: R and reload also unpause.
  void clear_divergence(bool unpause);

  void install_callbacks();
  void on_key(int key, int mods);
  void on_mouse_button(int button, int action, int mods);
  void on_cursor(double x, double y);

  ViewerOptions opts_;
  std::unique_ptr<GlfwWindow> window_;
  ViewerState st_;
  Session session_;
  // The renderer's pass clock, one span each (GL timestamps on a GPU, glFinish and a clock on llvmpipe).
  PassClock<1> sim_timer_{gl::gl_renderer_is_llvmpipe()}, render_timer_{gl::gl_renderer_is_llvmpipe()};
  Grab grab_;
  glm::vec3 grab_target_{0};
  // Alt-drag of a sphere or a mesh collider: its origin (and keyframes) follow the mouse in the
  // plane through the clicked point facing the camera; `moved` is how far they have been
  // shifted so far.
  struct SphereDrag {
    int sphere = -1;  // the index among the spheres, or among the meshes when `mesh`
    Grab plane;
    glm::vec3 start{0};
    glm::dvec3 moved{0.0};
    bool mesh = false;
  } sphere_drag_;
  glm::dvec2 cursor_{0};
  int drag_button_ = -1;
  bool drag_pan_ = false;
  int screenshots_ = 0;
  std::chrono::steady_clock::time_point last_contacts_{};
};

}  // namespace clothsim

// One simulation driven from Python (python/module.cpp binds it): a scene, its cloth and a
// backend, stepped a frame at a time. Plain C++ without pybind11, so it is the same code the
// command line runs: the scene loader, make_backend, the divergence check, stats_json,
// write_obj and the renderer. Errors are ExitError with the command line's codes and
// messages; the module turns 2 into ValueError, 3 into RuntimeError, 1 into DivergenceError.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"

namespace clothsim {

class Renderer;

class Session {
 public:
  Session(Scene scene, BackendKind kind);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Steps `frames` frames; a frame that fails the divergence check stops it with ExitError 1
  // (the command line's message), and the state stays at that frame.
  void step(int frames);
  // x, y, z per particle (the backend's scalar widened to double), in the cloth's order.
  std::vector<double> positions();
  // The Verlet velocity (x - x_prev) / dt of the last substep, as --stats measures it.
  std::vector<double> velocities();
  // Moves every particle to xyz (3 per particle); the velocities are kept.
  void set_positions(const std::vector<double>& xyz);
  nlohmann::json stats();
  void export_obj(const std::string& path);
  void render(const std::string& path, const std::string& shader, int width, int height);

  int64_t frame() const { return frame_; }
  size_t particles() const { return size_t(model_->count()); }
  const std::string& backend_name() const { return backend_name_; }
  const Scene& scene() const { return scene_; }
  // One call at a time per Session (steps release the GIL, so Python threads could overlap).
  std::mutex& mutex() { return mutex_; }

 private:
  // The GL context current on the calling thread for the span of one call, then released.
  struct Current;
  Scene scene_;
  std::unique_ptr<ClothModel> model_;
  std::unique_ptr<gl::GlContext> context_;  // the GPU backend's, or made by the first render()
  std::unique_ptr<Backend> backend_;
  std::unique_ptr<Renderer> renderer_;
  std::string backend_name_;  // read with the context current, once
  int64_t frame_ = 0;
  int64_t stepped_ = 0;  // frames stepped by this Session (stats' "frames")
  double wall_ = 0;      // seconds they took
  std::mutex mutex_;
};

}  // namespace clothsim

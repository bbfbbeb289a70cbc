// What the renderer tests share: an image read back from the offscreen target, the
// background test, and a Stage: a scene from scenes/, simulated by the GPU simulator and
// drawn offscreen from its own buffers.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "camera.hpp"
#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "renderer.hpp"
#include "texture.hpp"

namespace clothsim::test {

inline constexpr int kWidth = 160, kHeight = 120;
// Renderer::draw's clear colour (0.16, 0.17, 0.2) in 8 bits.
inline constexpr int kBackground[3] = {41, 43, 51};

struct Image {
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;  // top row first
  const uint8_t* at(int x, int y) const { return &rgba[(size_t(y) * w + size_t(x)) * 4]; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
};

inline bool is_background(const uint8_t* p) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(p[c]) - kBackground[c]) > 3) return false;
  return true;
}

inline int count_foreground(const Image& im) {
  int n = 0;
  for (int y = 0; y < im.h; ++y)
    for (int x = 0; x < im.w; ++x) n += !is_background(im.at(x, y));
  return n;
}

struct StageOptions {
  std::vector<std::string> sets{};  // --set overrides of the scene
  int samples = 4;                // of the offscreen target
  RendererOptions renderer{};
};

struct Stage {
  Scene scene;
  ClothModel model;
  GpuSimulator gpu;
  Renderer renderer;
  gl::RenderTarget target;
  OrbitCamera camera;

  explicit Stage(const std::string& name, int w = kWidth, int h = kHeight, const StageOptions& o = {})
      : scene(load_scene(source_path("scenes/" + name + ".json"), o.sets)), model(build_cloth(scene)),
        gpu(scene, model, source_path("compute")), renderer(CLOTHSIM_SOURCE_DIR, scene, model, o.renderer),
        target(w, h, o.samples), camera(default_camera(scene, model, float(w) / float(h))) {}

  void run(int frames) {
    for (int f = 0; f < frames; ++f) gpu.step_frame();
  }
  Image draw(const Appearance& look) {
    target.bind();
    renderer.place_colliders(gpu.constants());  // as render and the viewer do
    renderer.draw(gpu.state().positions(), gpu.state().normals(), camera, look);
    return {target.width(), target.height(), target.read_rgba()};
  }
  Image draw(ShaderKind shader) {
    Appearance look = Appearance::classic();
    look.shader = shader;
    return draw(look);
  }
  // Where a world point lands in the image (x right, y down, in pixels; pixel (i, j) spans [i, i+1)).
  glm::vec2 pixel_of(const glm::vec3& p) const {
    const glm::vec4 clip = camera.view_projection() * glm::vec4(p, 1.f);
    return {(clip.x / clip.w * 0.5f + 0.5f) * float(target.width()),
            (0.5f - clip.y / clip.w * 0.5f) * float(target.height())};
  }
  glm::vec3 position(int particle) {
    State<float> s;
    gpu.download(s);
    return glm::vec3(s.pos[size_t(particle)]);
  }
};

}  // namespace clothsim::test

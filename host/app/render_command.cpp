// `clothsim render SCENE --frames N --out DIR|FILE.png|FILE.mp4|FILE.gif [--shader NAME] [--size WxH]
// [--samples N] [--exposure E] [--every K] [--fps F] [--shadows on|off] [--ao on|off] [--studio on|off]
// [--floor] [--back-tint R,G,B] [--light X,Y,Z] [--load-state FILE] [--stats]`: simulates and draws
// headless (EGL, an offscreen multisampled framebuffer), frame by frame.
#include <cstdio>
#include <optional>
#include <regex>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "cli_common.hpp"
#include "export/output_plan.hpp"
#include "commands.hpp"
#include "gpu_simulator.hpp"
#include "image_output.hpp"
#include "renderer.hpp"

namespace clothsim {
namespace {

struct Opts {
  SceneOptions scene;
  int frames = 90;
  std::string out, shader = "Phong", size = "800x600", backend = "gpu", root;
  std::vector<float> camera;  // eye xyz, target xyz
  int lat = 40, lon = 40;
  int samples = 4;       // per pixel; 1 = no multisampling
  float exposure = 1.f;
  int every = 1;         // keep frames every, 2 * every, ...
  double fps = 0;        // of the video; 0 = the scene's rate / every
  std::string shadows = "on", occlusion = "on", studio = "on";
  bool floor = false, stats = false;
  std::vector<float> back_tint{0.7f, 0.78f, 0.95f};
  std::vector<float> light;  // empty: Appearance's default
  std::string load_path;     // --load-state: continue a saved run
};

// The cloth buffers to draw: the GPU simulator's own, or CPU results uploaded per frame
// (--backend cpu, for comparison).
struct FrameSource {
  // The GPU backend without a context of its own: it shares the renderer's.
  std::optional<GpuBackend> gpu;
  std::optional<CpuBackend<double>> cpu;
  gl::Buffer cpu_positions{"cpu positions"}, cpu_normals{"cpu normals"};

  void step_frame() {
    if (gpu) return gpu->step_frame();
    cpu->step_frame();
    const ClothSnapshot s = cpu->snapshot();
    std::vector<glm::vec4> p(s.pos.begin(), s.pos.end()), n(s.normal.begin(), s.normal.end());
    gl::upload_vector(cpu_positions, p);
    gl::upload_vector(cpu_normals, n);
  }
  // This frame's divergence check. Waiting for it costs nothing here: reading the image back
  // waits for the frame anyway.
  std::vector<FrameCheck> take_checks() { return gpu ? gpu->take_checks(true) : cpu->take_checks(true); }
  // Keyframed colliders move with the simulated time: draw them where this frame left them.
  void place_colliders(Renderer& r) const { gpu ? r.place_colliders(gpu->simulator().constants()) : r.place_colliders(cpu->constants()); }
  const gl::Buffer& positions() const { return gpu ? gpu->simulator().state().positions() : cpu_positions; }
  const gl::Buffer& normals() const { return gpu ? gpu->simulator().state().normals() : cpu_normals; }
  Backend& backend() { return gpu ? static_cast<Backend&>(*gpu) : *cpu; }
};

// Every file the render writes, checked before anything is simulated (output_plan.hpp).
OutputPlan plan_render_outputs(const Opts& o, const Scene& scene, const std::filesystem::path& root) {
  OutputPlan plan;
  plan.inputs_of(scene);
  plan.input("the state of --load-state", o.load_path);
  plan.inputs_in("a texture the renderer reads", (root / "textures").string());
  plan.inputs_in("a shader the renderer reads", (root / "shaders").string());
  const std::string ext = std::filesystem::path(o.out).extension().string();
  if (ext == ".png" || ext == ".mp4" || ext == ".gif") {
    plan.file("--out", o.out);
  } else {  // a folder of PNGs, frame_0000.png on: one per kept frame
    std::vector<std::string> names;
    for (int k = 0; k < o.frames / o.every; ++k) names.push_back(fmt::format("frame_{:04d}.png", k));
    plan.folder("--out", o.out, names);
  }
  return plan;
}

int run_render(const Opts& o) {
  std::smatch m;
  if (!std::regex_match(o.size, m, std::regex("([0-9]{1,5})x([0-9]{1,5})")))
    throw ExitError(kExitBadInput, fmt::format("--size {}: expected WIDTHxHEIGHT, e.g. 800x600", o.size));
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 16 || h < 16 || w > 8192 || h > 8192)
    throw ExitError(kExitBadInput, fmt::format("--size {}: each side must be in [16, 8192]", o.size));
  const auto shader = parse_shader(o.shader);
  if (!shader)
    throw ExitError(kExitBadInput, fmt::format("--shader {}: expected one of Wireframe, Normal, Diffuse, Phong, "
                                               "Texture, Bump, Displacement, Mirror", o.shader));
  if (o.every > o.frames)
    throw ExitError(kExitBadInput, fmt::format("--every {}: more than --frames {}, so no frame would be kept", o.every, o.frames));
  if (o.camera.size() != 0 && o.camera.size() != 6)
    throw ExitError(kExitBadInput, "--camera: expected six numbers: eye x,y,z then target x,y,z");
  Appearance look;
  if (!o.light.empty()) {
    const glm::vec3 l(o.light[0], o.light[1], o.light[2]);
    if (!(glm::length(l) > 1e-6f))
      throw ExitError(kExitBadInput, "--light: expected a direction X,Y,Z from the target to the light, not 0,0,0");
    // Only the direction is the user's: the light stays as far away as the default one.
    look.light = glm::normalize(l) * glm::length(look.light);
  }

  const Scene scene = o.scene.load();
  const double fps = o.fps > 0 ? o.fps : scene.simulation.frames_per_sec / o.every;
  FrameSink::check(o.out, w, h, fps);
  const auto root = find_project_root(o.root);
  check_outputs(plan_render_outputs(o, scene, root));
  const ClothModel model = build_cloth(scene);
  const BackendKind kind = parse_backend(o.backend);
  auto context = require_headless_context();
  std::optional<gl::RenderTarget> target;
  try {
    target.emplace(w, h, o.samples);
  } catch (const std::runtime_error& e) {
    throw ExitError(kExitBadInput, fmt::format("--samples {}: {}", o.samples, e.what()));
  }

  FrameSource source;
  if (kind == BackendKind::Gpu) source.gpu.emplace(nullptr, scene, model, root / "compute");
  else source.cpu.emplace(scene, model);
  if (!o.load_path.empty()) load_state(o.load_path, scene, model, source.backend());
  Renderer renderer(root, scene, model, {o.lat, o.lon});
  OrbitCamera camera = default_camera(scene, model, float(w) / float(h));
  if (o.camera.size() == 6)
    camera.look_from({o.camera[0], o.camera[1], o.camera[2]}, {o.camera[3], o.camera[4], o.camera[5]});
  look.shader = *shader;
  look.exposure = o.exposure;
  look.shadows = o.shadows == "on";
  look.ambient_occlusion = o.occlusion == "on";
  look.studio = o.studio == "on";
  look.floor = o.floor;
  look.back_tint = {o.back_tint[0], o.back_tint[1], o.back_tint[2]};
  renderer.set_timing(o.stats);
  if (o.floor && !scene.planes.empty())
    fmt::print(stderr, "render: --floor: {} has a plane, which is its floor; no other is drawn\n", scene.source);
  RenderTimes total{};
  int timed = 0, drawn = 0;
  FrameSink sink(o.out, w, h, fps);

  fmt::print("{}: {}, {} shader, {}x{}, {} samples/pixel, backend {}\n", scene.source, describe_cloth(model),
             kShaderNames[size_t(*shader)], w, h, o.samples, o.backend);
  Progress progress("render frame", o.frames);
  for (int f = 1; f <= o.frames; ++f) {
    source.step_frame();
    // Checked before drawing, so no frame of a diverged cloth is drawn: the frames before it
    // are written, then the run stops with the message.
    for (const FrameCheck& check : source.take_checks()) {
      const auto message = divergence_message(scene, model, check);
      if (!message) continue;
      progress.finish();
      if (f > 1) fmt::print("{}\n", sink.finish());
      throw ExitError(kExitCheckFailed, *message);
    }
    // Frames that are not kept are simulated but never drawn.
    if (f % o.every == 0 || (f == o.frames && sink.last_frame_only())) {
      target->bind();
      source.place_colliders(renderer);
      renderer.draw(source.positions(), source.normals(), camera, look);
      sink.add(target->read_rgba());
      // The first drawn frame builds the programs and targets: left out of the means when
      // there are more to average.
      if (o.stats && (drawn++ > 0 || o.frames / o.every < 2)) {
        const RenderTimes& t = renderer.times();
        total.shadow_ms += t.shadow_ms, total.occlusion_ms += t.occlusion_ms, total.shading_ms += t.shading_ms;
        total.gpu_timer = t.gpu_timer;
        ++timed;
      }
    }
    progress.update(f);
  }
  progress.finish();
  fmt::print("{}\n", sink.finish());
  if (o.stats && timed > 0) {
    const double n = double(timed);
    fmt::print("render passes, mean of {} drawn frames ({}): shadow map {:.2f} ms, ambient occlusion {:.2f} ms, "
               "shading {:.2f} ms, total {:.2f} ms/frame\n",
               timed, total.gpu_timer ? "GL timestamp queries" : "CPU clock + glFinish", total.shadow_ms / n,
               total.occlusion_ms / n, total.shading_ms / n, (total.shadow_ms + total.occlusion_ms + total.shading_ms) / n);
  }
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("render", "simulate and render headless to PNGs, an MP4 or a GIF");
  o->scene.add_to(*cmd, true);
  cmd->add_option("--frames", o->frames, "frames to simulate and render")->check(positive_number())->capture_default_str();
  cmd->add_option("--out", o->out, "DIR (frame_0000.png ...), FILE.png (the last frame), FILE.mp4 or FILE.gif")
      ->required();
  cmd->add_option("--shader", o->shader, "Wireframe, Normal, Diffuse, Phong, Texture, Bump, Displacement or Mirror")
      ->capture_default_str();
  cmd->add_option("--size", o->size, "image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--samples", o->samples, "multisample anti-aliasing: samples per pixel, 1 = off")
      ->check(number_in(1, 64))
      ->capture_default_str();
  cmd->add_option("--exposure", o->exposure, "light scale before the tone map (2 = one stop brighter)")
      ->check(number_in(0.01f, 100.f))
      ->capture_default_str();
  cmd->add_option("--every", o->every, "keep every K-th frame (frames K, 2K, ...), e.g. 2 for a GIF")
      ->check(positive_number())
      ->capture_default_str();
  cmd->add_option("--fps", o->fps, "frame rate of the MP4 or GIF (default: the scene's, divided by --every)")
      ->check(number_in(0.01, 1000.0));
  cmd->add_option("--backend", o->backend, "gpu, or cpu (reference positions uploaded per frame)")
      ->check(CLI::IsMember({"gpu", "cpu"}))
      ->capture_default_str();
  cmd->add_option("--camera", o->camera, "eye and target: EX,EY,EZ,TX,TY,TZ")->delimiter(',')->expected(6);
  cmd->add_option("-a", o->lat, "sphere latitude resolution")->check(number_in(3, 1000))->capture_default_str();
  cmd->add_option("-o", o->lon, "sphere longitude resolution")->check(number_in(3, 1000))->capture_default_str();
  cmd->add_option("--shadows", o->shadows, "soft shadows of the key light (lit shaders): on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--ao", o->occlusion, "screen-space ambient occlusion (lit shaders): on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--studio", o->studio, "background gradient, grid floor on planes, sky fill light: on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_flag("--floor", o->floor, "draw a studio floor under a scene without a plane (it does not collide)");
  cmd->add_option("--back-tint", o->back_tint, "R,G,B multiplying the colour of the cloth's back (1,1,1: none)")
      ->delimiter(',')
      ->expected(3)
      ->check(number_in(0.f, 4.f))
      ->capture_default_str();
  cmd->add_option("--light", o->light, "direction X,Y,Z from the camera's target to the key light (world axes)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--load-state", o->load_path, "start from a state saved by simulate --save-state (--frames more)")->check(non_empty_path());
  cmd->add_flag("--stats", o->stats, "time the drawing's passes and print their mean per frame");
  cmd->add_option("-r,--root", o->root, "project root (shaders/, compute/, textures/)");
  cmd->callback([o, &run] { run = [o] { return run_render(*o); }; });
}

}  // namespace clothsim

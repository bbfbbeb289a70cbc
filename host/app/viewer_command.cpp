// `clothsim [SCENE] [-f SCENE] [-a LAT] [-o LON] [-r ROOT] [--frames N --screenshot FILE.png]`:
// the interactive viewer, the default command, with the classic flags.
#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gpu_simulator.hpp"
#include "export/output_plan.hpp"
#include "viewer.hpp"

namespace clothsim {

void add_viewer_options(CLI::App& app, std::function<int()>& run) {
  struct Opts {
    std::string positional, file, root, screenshot, size = "1280x800";
    std::vector<std::string> sets;
    int lat = 40, lon = 40, frames = -1;
  };
  auto o = std::make_shared<Opts>();
  CLI::Option* positional = app.add_option("scene", o->positional, "scene JSON file for the viewer (default: the built-in pinned2)");
  CLI::Option* file = app.add_option("-f", o->file, "scene JSON file (the classic flag)");
  app.add_option("-a", o->lat, "sphere latitude resolution")->check(number_in(3, 1000))->capture_default_str();
  app.add_option("-o", o->lon, "sphere longitude resolution")->check(number_in(3, 1000))->capture_default_str();
  app.add_option("-r", o->root, "project root with shaders/, compute/, textures/ (found automatically)");
  app.add_option("--set", o->sets, "override a scene value, e.g. --set cloth.ks=500 (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  app.add_option("--frames", o->frames, "scripted: run N frames unpaused, save --screenshot, exit")
      ->check(non_negative_number());
  app.add_option("--screenshot", o->screenshot, "scripted: PNG of the window (panels included) after --frames");
  add_no_cache_flag(app);
  app.add_option("--window", o->size, "window size WIDTHxHEIGHT")->capture_default_str();
  app.final_callback([o, &app, &run, positional, file] {
    if (app.get_subcommands().size() > 0) return;  // a subcommand ran its own callback
    // An empty name given as the scene is no scene file, not "the built-in one".
    const bool empty_given = (positional->count() > 0 && o->positional.empty()) || (file->count() > 0 && o->file.empty());
    run = [o, empty_given]() -> int {
      if (empty_given) throw ExitError(kExitBadInput, "scene \"\": an empty path (expected a scene JSON file)");
      if (!o->positional.empty() && !o->file.empty())
        throw ExitError(kExitBadInput, "give the scene once: either SCENE or -f SCENE");
      if ((o->frames >= 0) != !o->screenshot.empty())
        throw ExitError(kExitBadInput, "--frames and --screenshot go together (scripted mode)");
      ViewerOptions v;
      v.root = find_project_root(o->root);
      v.scene_path = o->file.empty() ? o->positional : o->file;
      v.sets = o->sets;
      v.sphere_lat = o->lat;
      v.sphere_lon = o->lon;
      v.frames = o->frames;
      v.screenshot = o->screenshot;
      if (!v.screenshot.empty()) {  // before the window opens: never a run that ends in a refusal
        OutputPlan plan;
        plan.inputs_of(v.scene_path.empty() ? default_scene(v.sets) : load_scene(v.scene_path, v.sets));
        plan.inputs_in("a texture the viewer reads", (v.root / "textures").string());
        plan.inputs_in("a shader the viewer reads", (v.root / "shaders").string());
        plan.file("--screenshot", v.screenshot);
        check_outputs(plan);
      }
      if (std::sscanf(o->size.c_str(), "%dx%d", &v.width, &v.height) != 2 || v.width < 64 || v.height < 64)
        throw ExitError(kExitBadInput, fmt::format("--window {}: expected WIDTHxHEIGHT, at least 64x64", o->size));
      return run_viewer(v);
    };
  });
}

}  // namespace clothsim

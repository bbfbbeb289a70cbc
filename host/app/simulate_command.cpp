// `clothsim simulate SCENE --frames N [--backend gpu|cpu] [--export FILE.obj|FILE.pc2|DIR/]
//  [--export-every K] [--export-mesh FILE.obj] [--export-colliders DIR/] [--load-state FILE]
//  [--save-state FILE] [--stats] [--profile] [--stats-json FILE]
//  [--intersections-every K] [--stretch-every K]`
// Every output replaces the file it names only once complete (docs/export.md).
#include <algorithm>

#include <chrono>
#include <filesystem>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"
#include "export/frame_export.hpp"
#include "analysis/intersections.hpp"
#include "colliders/mesh_collider.hpp"
#include "export/collider_export.hpp"
#include "export/output_plan.hpp"
#include "run_stats.hpp"

namespace clothsim {
namespace {

void print_stats(const Scene& scene, const ClothModel& model, const ClothStats& st, int frames, double wall,
                 const Backend& backend) {
  const int substeps = frames * scene.simulation.simulation_steps;
  fmt::print("frames            {}\n", frames);
  fmt::print("substeps          {}\n", substeps);
  fmt::print("wall time         {:.3f} s ({:.2f} ms/frame)\n", wall, frames ? 1e3 * wall / frames : 0.0);
  fmt::print("max stretch       {:.4f} x rest length\n", st.max_stretch_ratio);
  fmt::print("stretch p99       {:.4f} x rest length (99 % of the springs at most)\n", st.p99_stretch_ratio);
  if (const uint64_t settling = backend.stretch_settling_passes(); settling > 0)
    fmt::print("settling passes   {} ({:.2f} a substep; stretch_passes_max)\n", settling,
               substeps ? double(settling) / substeps : 0.0);
  fmt::print("kinetic energy    {:.6g} J (max speed {:.4g} m/s)\n", st.kinetic, st.max_speed);
  if (st.sphere_clearance.size() > 8) {
    // A collider built of many spheres (a round table): the closest one says what matters.
    const auto least = std::min_element(st.sphere_clearance.begin(), st.sphere_clearance.end());
    fmt::print("spheres ({}) least clearance {:.6f} m (sphere[{}])\n", st.sphere_clearance.size(), *least,
               least - st.sphere_clearance.begin());
  } else {
    for (size_t k = 0; k < st.sphere_clearance.size(); ++k)
      fmt::print("sphere[{}] clearance {:.6f} m\n", k, st.sphere_clearance[k]);
  }
  for (size_t k = 0; k < st.plane_clearance.size(); ++k)
    fmt::print("plane[{}] clearance  {:.6f} m\n", k, st.plane_clearance[k]);
  for (size_t k = 0; k < st.mesh_clearance.size(); ++k)
    fmt::print("mesh[{}] clearance   {:.6f} m (to its surface; thickness {} m)\n", k, st.mesh_clearance[k],
               scene.meshes[k].thickness);
  if (st.seam_pairs > 0)
    fmt::print("seams             {} sewn pairs, the widest {:.3f} mm apart\n", st.seam_pairs, st.max_seam_gap * 1e3);
  for (size_t k = 0; k < st.mesh_inside.size(); ++k)
    fmt::print("mesh[{}] inside      {} of {} masses (winding number above 1/2)\n", k, st.mesh_inside[k],
               model.count());
  // Names a mesh file that the scene file named: printed escaped.
  for (const std::string& line : collider_mesh_report()) fmt::print("mesh collider     {}\n", printable(line));
  fmt::print("finite            {}\n", st.finite ? "yes" : "NO (a value became NaN/Inf)");
}

// Every file the run writes, checked before it starts (output_plan.hpp): frames of a
// sequence from `start`, the frame the run begins at.
OutputPlan plan_outputs(const Scene& scene, ExportKind kind, const std::string& export_path,
                        const std::string& export_mesh, const std::string& load_path, const std::string& save_path,
                        const std::string& colliders_path, const std::string& stats_path, int64_t start, int frames,
                        int every) {
  OutputPlan plan;
  plan.inputs_of(scene);
  plan.input("the state of --load-state", load_path);
  if (kind == ExportKind::Obj) plan.file("--export", export_path);
  if (kind == ExportKind::PointCache) {
    plan.file("--export", export_path);
    const std::string by = fmt::format("--export {}", export_path);
    if (export_mesh.empty())
      plan.companion("--export", mesh_beside_cache(export_path), "the mesh written beside " + by);
    else
      plan.file("--export-mesh", export_mesh);
    plan.companion("--export", partial_cache_path(export_path), "where " + by + " keeps the frames of a run that stops early");
  }
  if (kind == ExportKind::ObjSequence) {
    std::vector<std::string> names;
    for (int64_t f = start; f <= start + frames; f += every) names.push_back(fmt::format("frame_{:04d}.obj", f));
    plan.folder("--export", export_path, names);
  }
  if (!colliders_path.empty()) plan_collider_export(plan, scene, colliders_path, start, frames, every);
  if (!save_path.empty()) plan.file("--save-state", save_path);
  if (!stats_path.empty()) plan.file("--stats-json", stats_path);
  return plan;
}

void save_state(const std::string& path, const Scene& scene, const ClothModel& model, Backend& backend) {
  Checkpoint c;
  c.cloth = cloth_hash(model);
  c.nw = model.nw;
  c.nh = model.nh;
  c.pins = pinned_count(model);
  c.scene = scene.source;
  c.backend = backend.name();
  c.state = backend.save_state();
  try {
    write_checkpoint(path, c);
  } catch (const CheckpointError& e) {
    throw ExitError(kExitBadInput, fmt::format("--save-state {}", e.what()));
  }
  fmt::print("saved {} (frame {})\n", path, c.state.frame);
}

}  // namespace

void add_simulate_command(CLI::App& app, std::function<int()>& run) {
  struct Opts {
    SceneOptions scene;
    int frames = 90;
    std::string backend = "gpu";
    std::string export_path, export_mesh, load_path, save_path, colliders_path, stats_path;
    int export_every = 1;
    bool stats = false, profile = false;
    int intersections_every = 0;
    int stretch_every = 0;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("simulate", "run a scene headless and report or export the result");
  o->scene.add_to(*cmd, true);
  cmd->add_option("--frames", o->frames, "frames to simulate")->check(non_negative_number());
  cmd->add_option("--backend", o->backend, "gpu (compute shaders) or cpu (the reference)")
      ->check(CLI::IsMember({"gpu", "cpu"}))
      ->capture_default_str();
  cmd->add_option("--export", o->export_path,
                  "FILE.obj: the final cloth; FILE.pc2: a point cache of every frame plus FILE.obj, the mesh; "
                  "DIR/: DIR/frame_0000.obj, one OBJ per frame");
  cmd->add_option("--export-mesh", o->export_mesh,
                  "with --export FILE.pc2: where the mesh goes (default FILE.obj beside it, which is written only "
                  "if absent or already that mesh)");
  cmd->add_option("--export-colliders", o->colliders_path,
                  "DIR/: every mesh collider as it stands at each exported frame, DIR/mesh0/frame_0000.obj, ... "
                  "(the frames of --export DIR/ or FILE.pc2, or every --export-every-th)");
  cmd->add_option("--export-every", o->export_every, "with a .pc2 or DIR/ export or --export-colliders: write every K-th frame")
      ->check(positive_number());
  cmd->add_option("--load-state", o->load_path, "continue from a state saved by --save-state")->check(non_empty_path());
  cmd->add_option("--save-state", o->save_path, "save the final state (positions, displacements, time)");
  cmd->add_flag("--stats", o->stats, "print frames, timing, stretch, energy, clearances, self-intersections");
  cmd->add_flag("--profile", o->profile,
                "time every pass on its own (a glFinish around each on the GPU) and print their ms per frame");
  cmd->add_option("--stats-json", o->stats_path, "write the --stats figures to FILE as JSON (docs/python.md lists the keys)")
      ->check(non_empty_path());
  cmd->add_option("--intersections-every", o->intersections_every,
                  "every K-th frame print the exact self-intersection count (CPU, reads the frame back)")
      ->check(positive_number());
  cmd->add_option("--stretch-every", o->stretch_every,
                  "every K-th frame print the largest and the 99th-percentile spring stretch (reads the frame back)")
      ->check(positive_number());
  cmd->callback([o, &run] {
    run = [o]() -> int {
      const ExportKind kind = export_kind(o->export_path);
      const bool sequence = kind == ExportKind::PointCache || kind == ExportKind::ObjSequence;
      const bool colliders = !o->colliders_path.empty();
      if (o->export_every != 1 && !sequence && !colliders)
        throw ExitError(kExitBadInput, "--export-every: needs --export FILE.pc2, --export DIR/ or --export-colliders DIR/ "
                                       "(an OBJ holds one frame)");
      if (!o->export_mesh.empty() && kind != ExportKind::PointCache)
        throw ExitError(kExitBadInput, "--export-mesh: needs --export FILE.pc2 (the mesh the point cache deforms)");
      const Scene scene = o->scene.load();
      if (colliders && scene.meshes.empty())
        throw ExitError(kExitBadInput, fmt::format("--export-colliders: {} has no mesh collider (scene key `mesh`) to "
                                                   "export", scene.source));
      auto plan = [&](int64_t start) {
        return plan_outputs(scene, kind, o->export_path, o->export_mesh, o->load_path, o->save_path, o->colliders_path,
                            o->stats_path, start, o->frames, o->export_every);
      };
      check_outputs(plan(0));  // before anything is built: a bad output fails at once
      const ClothModel model = build_cloth(scene);
      std::unique_ptr<Backend> backend = make_backend(parse_backend(o->backend), scene, model);
      fmt::print("{}: {}, {} substeps/frame, backend {}\n", scene.source, describe_cloth(model),
                 scene.simulation.simulation_steps, backend->name());
      const int64_t start = o->load_path.empty() ? 0 : load_state(o->load_path, scene, model, *backend);
      if (start != 0) check_outputs(plan(start));  // a sequence's frames are numbered from the state's
      auto export_obj = [&](const ClothSnapshot& snap, const std::string& what) {
        try {
          write_obj(o->export_path, model, snap);
        } catch (const std::runtime_error& e) {
          throw ExitError(kExitBadInput, fmt::format("--export {}", e.what()));
        }
        fmt::print("wrote {}{}\n", o->export_path, what);
      };
      // Sequences are written as the frames come: the start state now, then every K-th frame.
      std::unique_ptr<FrameExport> frames;
      // A write that fails is exit 2 naming the option that asked for it.
      auto guarded = [&](const char* option, auto&& write) {
        try {
          write();
        } catch (const std::runtime_error& e) {
          throw ExitError(kExitBadInput, fmt::format("{} {}", option, e.what()));
        }
      };
      auto export_guarded = [&](auto&& write) { guarded("--export", write); };
      if (sequence)
        export_guarded([&] {
          frames = open_frame_export(kind, o->export_path, model, start, o->export_every, backend->snapshot(),
                                     o->export_mesh);
        });
      std::unique_ptr<ColliderExport> collider_frames;
      auto colliders_guarded = [&](auto&& write) { guarded("--export-colliders", write); };
      if (colliders)
        colliders_guarded([&] {
          collider_frames = std::make_unique<ColliderExport>(scene, o->colliders_path, start, o->export_every);
          collider_frames->add(start, backend->time());
        });
      Progress progress(frames ? "export frame" : "frame", o->frames);
      // A diverged run stops with the message. A sequence keeps the frames written so far (all
      // passed the check); a single OBJ gets the newest frame that passed; no state is saved.
      auto stop_if_diverged = [&](const std::vector<FrameCheck>& checks) {
        for (const FrameCheck& check : checks) {
          const auto message = divergence_message(scene, model, check);
          if (!message) continue;
          progress.finish();
          if (frames) {
            // A sequence keeps its OBJs; a PC2 stays PATH.partial and PATH is left as it was.
            std::string said;
            export_guarded([&] { said = frames->finish_incomplete("the divergence"); });
            fmt::print("{}\n", said);
          } else if (kind == ExportKind::Obj) {
            int kept = 0;
            const ClothSnapshot good = backend->last_good(&kept);
            export_obj(good, fmt::format(" (frame {}, the last one that passed the divergence check)", kept));
          }
          if (!o->save_path.empty()) fmt::print(stderr, "--save-state {}: not saved, the run diverged\n", o->save_path);
          throw ExitError(kExitCheckFailed, *message);
        }
      };
      PassProfile profile;
      if (o->profile) backend->set_profile(&profile);
      const auto t0 = std::chrono::steady_clock::now();
      for (int f = 1; f <= o->frames; ++f) {
        backend->step_frame();
        const int64_t frame = start + f;
        const bool write = frames && frames->wants(frame);
        // The divergence check: on the GPU a reduction whose 32-byte result arrives at most one
        // frame late, so the loop never waits for the frame it has just queued. A frame to be
        // written is read back anyway, so its check is waited for: no failed frame is exported.
        stop_if_diverged(backend->take_checks(write));
        if (write) export_guarded([&] { frames->add(frame, backend->snapshot()); });
        if (collider_frames && collider_frames->wants(frame))
          colliders_guarded([&] { collider_frames->add(frame, backend->time()); });
        if (o->intersections_every > 0 && f % o->intersections_every == 0) {
          // A line of its own per frame, so a script can collect them (scripts/contact-check).
          progress.finish();  // clears the progress line; update() redraws it
          fmt::print("frame {} self-intersections {}\n", frame, count_self_intersections(model, backend->snapshot()));
          std::fflush(stdout);  // a script reading a pipe sees each line as it comes
        }
        if (o->stretch_every > 0 && f % o->stretch_every == 0) {
          progress.finish();
          const ClothStats st = measure(scene, model, backend->snapshot(), backend->time());
          fmt::print("frame {} max stretch {:.4f} p99 {:.4f}\n", frame, st.max_stretch_ratio, st.p99_stretch_ratio);
          std::fflush(stdout);
        }
        progress.update(f);
      }
      stop_if_diverged(backend->take_checks(true));
      progress.finish();
      backend->set_profile(nullptr);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (frames) {
        export_guarded([&] { frames->finish(); });
        fmt::print("wrote {}\n", frames->summary());
      }
      if (collider_frames) {
        colliders_guarded([&] { collider_frames->finish(); });
        fmt::print("wrote {}\n", collider_frames->summary());
      }
      if (o->stats || kind == ExportKind::Obj) {
        const ClothSnapshot snap = backend->snapshot();
        if (o->stats) print_stats(scene, model, measure(scene, model, snap, backend->time()), o->frames, wall, *backend);
        if (o->stats)  // exact, on the CPU: only asked for here
          fmt::print("self-intersections {} (pairs of non-adjacent triangles)\n", count_self_intersections(model, snap));
        if (kind == ExportKind::Obj) export_obj(snap, "");
      }
      if (o->profile)
        print_profile(profile, o->frames, o->backend == "gpu" ? "glFinish before and after each" : "the CPU reference");
      if (!o->stats_path.empty())
        guarded("--stats-json", [&] {
          nlohmann::json j = stats_json(scene, model, *backend, o->frames, wall);
          if (o->profile) j["pass_ms_per_frame"] = profile_json(profile, o->frames);
          write_stats_json(o->stats_path, j);
        });
      if (!o->save_path.empty()) save_state(o->save_path, scene, model, *backend);
      return kExitOk;
    };
  });
}

}  // namespace clothsim

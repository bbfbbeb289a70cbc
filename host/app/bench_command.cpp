// `clothsim bench [--sizes ...] [--backend gpu,cpu] [--frames N] [--self-collision on|off|both]
// [--json FILE]`: throughput of both backends on square cloths (pinned corners, a sphere, a plane).
#include <chrono>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench_runner.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "io/output_file.hpp"
#include "export/output_plan.hpp"
#include "gpu_simulator.hpp"

namespace clothsim {

namespace {

// The self-collision passes of one frame in a result's per-pass times: the GPU's five stages
// (count_cells .. resolve_self_contacts), or the reference's collide_self.
double self_collision_ms(const BenchResult& r) {
  double ms = 0;
  for (const char* pass : {"count_cells", "scan_cells", "fill_cells", "sort_cells", "resolve_self_contacts", "collide_self"})
    if (auto it = r.pass_ms.find(pass); it != r.pass_ms.end()) ms += it->second;
  return ms;
}


// One configuration's ms/frame, by backend, solver, size and self-collision.
using Timings = std::map<std::tuple<std::string, std::string, int, bool>, double>;

// The side-by-side figures a bench of several solvers or both backends is run for (issue 22's
// cost check): each solver's ms/frame over classic's on the same backend, and the GPU path's
// speed over the CPU reference's, per size. Only pairs that both ran are printed.
void print_ratios(const Timings& ms, const std::vector<int>& sizes, const std::vector<bool>& sc_modes) {
  auto find = [&](const std::string& backend, const std::string& solver, int n, bool sc) {
    auto it = ms.find({backend, solver, n, sc});
    return it == ms.end() ? 0.0 : it->second;
  };
  for (bool sc : sc_modes)
    for (int n : sizes) {
      std::string line;
      for (const char* backend : {"gpu", "cpu"})
        for (Solver s : kBenchSolvers) {
          const char* solver = solver_name(s);
          const double a = find(backend, solver, n, sc), b = find(backend, "classic", n, sc);
          if (s != Solver::Classic && a > 0 && b > 0) line += fmt::format("  {} {}/classic {:.2f}", backend, solver, a / b);
        }
      for (Solver s : kBenchSolvers) {
        const char* solver = solver_name(s);
        const double g = find("gpu", solver, n, sc), c = find("cpu", solver, n, sc);
        if (g > 0 && c > 0) line += fmt::format("  {} gpu/cpu speed {:.2f}x", solver, c / g);
      }
      if (!line.empty()) fmt::print("{}x{} self-collision {}:{}\n", n, n, sc ? "on" : "off", line);
    }
}

struct Opts {
  std::vector<int> sizes{32, 64, 128, 256, 512, 1024};
  std::vector<std::string> backends{"gpu", "cpu"};
  std::vector<std::string> solvers = solver_names();
  int frames = 10;
  std::string self_collision = "both", json_path, root;
  double cpu_limit_s = 60;
};

int run_bench(const Opts& o) {
  std::vector<bool> sc_modes;
  if (o.self_collision != "on") sc_modes.push_back(false);
  if (o.self_collision != "off") sc_modes.push_back(true);
  for (int n : o.sizes)
    if (n < 3 || n > 4096) throw ExitError(kExitBadInput, fmt::format("--sizes: {} is outside [3, 4096]", n));
  for (auto& b : o.backends) parse_backend(b);
  if (!o.json_path.empty()) {  // checked before the minutes of timing, not after
    OutputPlan plan;
    plan.inputs_in("a shader bench reads", (find_project_root(o.root) / "compute").string());
    plan.file("--json", o.json_path);
    check_outputs(plan);
  }

  BenchRunner runner(o.root, o.frames);
  nlohmann::json out = {{"gl_renderer", runner.renderer()}, {"frames", o.frames}, {"results", nlohmann::json::array()},
                        {"skipped", nlohmann::json::array()}};
  fmt::print("{:>7} {:>9} {:>5} {:>4} {:>9} {:>7} {:>10} {:>10} {:>14} {:>6} {:>8} {:>6} {:>9}\n", "backend", "solver",
             "size", "self", "particles", "colours", "ms/frame", "self ms", "p-substeps/s", "disp", "disp/sub", "barr",
             "GPU MiB");
  Timings timings;
  int done = 0;
  const int total = int(o.sizes.size() * o.backends.size() * sc_modes.size() * o.solvers.size());
  Progress progress("bench configuration", total);
  for (const auto& backend : o.backends)
    for (const auto& solver : o.solvers)
    for (bool sc : sc_modes)
      for (int n : o.sizes) {
        progress.update(done);
        const Scene scene = bench_scene(n, sc, solver_of(solver));
        if (backend == "cpu") {
          const double estimate = runner.estimate_cpu_seconds(scene);
          if (estimate > o.cpu_limit_s) {
            const std::string why = fmt::format("cpu {} {}x{} self-collision {}: skipped, estimated {:.0f} s > {:.0f} s",
                                                solver, n, n, sc ? "on" : "off", estimate, o.cpu_limit_s);
            progress.finish();
            fmt::print("{}\n", why);
            out["skipped"].push_back(why);
            ++done;
            continue;
          }
        }
        const BenchResult r = backend == "gpu" ? runner.run_gpu(scene) : runner.run_cpu(scene);
        progress.finish();
        // "self ms": the self-collision passes of one frame (the hash's stages and the
        // response), from the per-pass timing of a separate frame.
        fmt::print("{:>7} {:>9} {:>5} {:>4} {:>9} {:>7} {:>10.3f} {:>10} {:>14.3e} {:>6} {:>8.1f} {:>6} {:>9.1f}\n",
                   backend, solver, n, sc ? "on" : "off", r.particles, r.colours, r.ms_per_frame,
                   sc ? fmt::format("{:.3f}", self_collision_ms(r)) : std::string("-"),
                   r.particle_substeps_per_s, r.dispatches_per_frame,
                   r.dispatches_per_frame / r.substeps_per_frame, r.barriers_per_frame,
                   r.gpu_memory_bytes / 1048576.0);
        out["results"].push_back(to_json(r, backend, solver, n, sc));
        timings[{backend, solver, n, sc}] = r.ms_per_frame;
        ++done;
      }
  progress.finish();
  print_ratios(timings, o.sizes, sc_modes);
  if (!o.json_path.empty()) {
    // Beside the named file first and renamed once complete (output_file.hpp): an old result is
    // never left half written.
    try {
      write_text_replacing(o.json_path, out.dump(2) + "\n");
    } catch (const std::exception& e) {
      throw ExitError(kExitBadInput, fmt::format("--json: {}", e.what()));
    }
    fmt::print("wrote {}\n", o.json_path);
  }
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("bench", "measure throughput of the GPU and CPU backends on square cloths");
  cmd->add_option("--sizes", o->sizes, "cloth sizes (points per side), comma separated")->delimiter(',')->capture_default_str();
  cmd->add_option("--backend", o->backends, "gpu, cpu or gpu,cpu")->delimiter(',')->capture_default_str();
  cmd->add_option("--solver", o->solvers, "classic, fabric, or a list: classic,fabric (simulation.solver)")
      ->delimiter(',')
      ->check(CLI::IsMember(solver_names()))
      ->capture_default_str();
  cmd->add_option("--frames", o->frames, "timed frames per configuration (after 2 warm-up frames)")
      ->check(positive_number())
      ->capture_default_str();
  cmd->add_option("--self-collision", o->self_collision, "on, off or both")
      ->check(CLI::IsMember({"on", "off", "both"}))
      ->capture_default_str();
  cmd->add_option("--json", o->json_path, "write the results as JSON");
  cmd->add_option("--cpu-limit", o->cpu_limit_s, "skip CPU runs estimated to take longer (seconds)")->capture_default_str();
  cmd->add_option("-r,--root", o->root, "project root (compute/)");
  cmd->callback([o, &run] { run = [o] { return run_bench(*o); }; });
}

}  // namespace clothsim

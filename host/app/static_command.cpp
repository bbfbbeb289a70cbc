// `clothsim static SCENE [--export FILE.obj] [--tolerance NEWTONS] [--max-iterations N]`: the
// cloth's static equilibrium by Newton's method in double (static_solve.hpp), independent of both
// solvers: where a run of the scene should come to rest. The physical answer a solver's rest
// state is compared with (scripts/hang-resolution prints it next to each solver's sag).
#include <algorithm>
#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"
#include "analysis/diagnostics.hpp"
#include "analysis/divergence.hpp"
#include "export/output_plan.hpp"
#include "analysis/static_solve.hpp"

namespace clothsim {
namespace {

struct Opts {
  SceneOptions scene;
  std::string export_path;
  double tolerance = 1e-10;
  int max_iterations = 200;
};

int run_static(const Opts& o) {
  const Scene scene = o.scene.load();
  if (!o.export_path.empty()) {
    OutputPlan plan;
    plan.inputs_of(scene);
    plan.file("--export", o.export_path);
    check_outputs(plan);
  }
  const ClothModel model = build_cloth(scene);
  fmt::print("{}: {}, static equilibrium (Newton, double)\n", scene.source, describe_cloth(model));
  // Nothing free to move: the cloth rests where it starts. Exit 0 (the answer is exact), said
  // plainly so a scene whose pins cover everything by mistake is noticed.
  if (std::all_of(model.pinned.begin(), model.pinned.end(), [](uint8_t p) { return p != 0; }))
    fmt::print("nothing to solve: every particle is pinned (the cloth rests where it starts)\n");
  StaticEquilibrium eq;
  try {
    eq = solve_static_equilibrium(scene, model, o.tolerance, o.max_iterations);
  } catch (const std::invalid_argument& e) {
    // Colliders, wind or self-collision: what the solve leaves out is the scene's, so exit 2.
    throw ExitError(kExitBadInput, fmt::format("{}: {}", scene.source, e.what()));
  }
  // At rest (no displacement), with normals for the OBJ: the divergence guard's snapshot of positions.
  std::vector<glm::dvec4> pos;
  for (int i = 0; i < model.count(); ++i)
    pos.emplace_back(eq.pos[size_t(i)], model.pinned[size_t(i)] ? 0.0 : 1.0 / model.mass[size_t(i)]);
  const ClothSnapshot snap = snapshot_of_positions(model, pos);
  const ClothStats st = measure(scene, model, snap);
  fmt::print("newton steps      {}\n", eq.iterations);
  fmt::print("largest net force {:.3g} N (tolerance {:.3g} N)\n", eq.residual, o.tolerance);
  fmt::print("max stretch       {:.6f} x rest length\n", st.max_stretch_ratio);
  fmt::print("stretch p99       {:.6f} x rest length (99 % of the springs at most)\n", st.p99_stretch_ratio);
  fmt::print("spring energy     {:.6g} J\n", st.spring);
  if (!o.export_path.empty()) {
    try {
      write_obj(o.export_path, model, snap);
    } catch (const std::runtime_error& e) {
      throw ExitError(kExitBadInput, fmt::format("--export {}", e.what()));
    }
    fmt::print("wrote {}\n", o.export_path);
  }
  if (!eq.converged) {
    fmt::print(stderr, "static: {}: Newton's method did not converge in {} steps (largest net force {:.3g} N, "
                       "asked {:.3g} N); raise --max-iterations or --tolerance\n",
               scene.source, eq.iterations, eq.residual, o.tolerance);
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace

void add_static_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("static", "the cloth's static equilibrium (Newton's method, CPU, double)");
  o->scene.add_to(*cmd, true);
  cmd->add_option("--export", o->export_path, "FILE.obj: the cloth at rest (written once complete)");
  cmd->add_option("--tolerance", o->tolerance, "stop when no free mass has a net force above this (N)")
      ->check(positive_number())
      ->capture_default_str();
  cmd->add_option("--max-iterations", o->max_iterations, "Newton steps at most")
      ->check(number_in(1, 100000))
      ->capture_default_str();
  cmd->callback([o, &run] { run = [o] { return run_static(*o); }; });
}

}  // namespace clothsim

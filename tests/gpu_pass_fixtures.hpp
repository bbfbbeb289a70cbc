// Scenes, comparisons and runners shared by the GPU pass and run tests (one translation unit each).
#pragma once

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>
#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "pass_check.hpp"
#include "reference/reference.hpp"
#include "test_helpers.hpp"

using namespace clothsim;
using test::mismatches;

namespace pass_fixtures {

using Vec4s = std::vector<Vec4<float>>;

// Off llvmpipe: one pass from an identical state (the `validate` default), and a short run,
// whose few-ULP differences the Verlet velocity carries on for a while (docs/design.md §6).
inline constexpr double kPassTolerance = 1e-5;  // m
inline constexpr double kRunTolerance = 1e-4;   // m, after at most 50 substeps

inline std::filesystem::path compute_dir() { return test::source_path("compute"); }

// A horizontal cloth (y = 1) pinned at the middles of its four edges and at the (1, 1) corner
// (inside the sphere: it keeps the squeezed patch from sliding out), with self-collision off. A big sphere pokes up through the quarter around the (1, 1) corner and presses it
// against a ceiling plane (normal down) lower than the sphere's top: in every substep the
// sphere pushes particles up through the plane, the plane pushes them back, and the springs
// between the tent and the pins are stretched past max_stretch. The tent covers the last
// particles in index order, so the last, partial workgroup has contacts too; the other
// corners sag under gravity. check_exercised() below counts all of that.
inline const char* const kSphereAndPlane = R"(,
  "sphere": {"origin": [0.9, 0.75, 0.9], "radius": 0.45, "friction": 0.3},
  "plane": {"point": [0.0, 1.1, 0.0], "normal": [0.0, -1.0, 0.0], "friction": 0.5})";
// The same, plus a second, smaller and frictionless sphere near the (0, 0) corner, and a
// sloping frictionless ceiling that presses the cloth onto it.
inline const char* const kTwoSpheresTwoPlanes = R"(,
  "sphere": [{"origin": [0.9, 0.75, 0.9], "radius": 0.45, "friction": 0.3},
             {"origin": [0.25, 0.93, 0.3], "radius": 0.15, "friction": 0.0}],
  "plane": [{"point": [0.0, 1.1, 0.0], "normal": [0.0, -1.0, 0.0], "friction": 0.5},
            {"point": [0.25, 1.05, 0.3], "normal": [0.1, -1.0, 0.2], "friction": 0.0}])";
// Velocities and stretched springs, not just the start; on the 131x129 cloth the tent slides
// off the last particles after about 2 frames (since Provot keeps masses out of the sphere).
inline constexpr int kWarmupFrames = 1;

inline Scene pressed_cloth(int nw, int nh, std::vector<std::string> sets = {}, const char* colliders = kSphereAndPlane,
                    int orientation = 0) {
  sets.push_back(fmt::format("cloth.pinned=[[{0},0],[0,{1}],[{2},{1}],[{0},{3}],[{2},{3}]]", nw / 2, nh / 2, nw - 1, nh - 1));
  sets.push_back("simulation.self_collision=false");
  return test::make_scene(nw, nh, orientation, sets, colliders);
}

// GPU == CPU bit for bit on llvmpipe, else within `tolerance` metres per particle.
inline void check_same(const char* what, const Vec4s& gpu, const Vec4s& cpu, double tolerance) {
  const Deviation d = deviation(gpu, cpu);
  INFO(what << ": max |GPU - CPU| = " << d.max << " m, RMS " << d.rms << " m, " << mismatches(gpu, cpu) << " of "
            << cpu.size() << " differ in some bit");
  REQUIRE(gpu.size() == cpu.size());
  if (gl::gl_renderer_is_llvmpipe())
    CHECK(mismatches(gpu, cpu) == 0);
  else
    CHECK(d.max <= tolerance);
}

// Every pass of `scene` from the state after `warmup_frames` CPU frames, as `validate` checks
// them: bit for bit on llvmpipe, else within kPassTolerance.
inline void check_every_pass_alike(const Scene& scene, const ClothModel& model, int warmup_frames) {
  GpuSimulator gpu(scene, model, compute_dir());
  for (const PassError& e : check_passes(scene, model, gpu, warmup_frames)) {
    INFO(e.pass << ": max |GPU - CPU| = " << e.max_error << " m");
    if (gl::gl_renderer_is_llvmpipe()) CHECK(e.bitwise);
    else CHECK(e.max_error <= kPassTolerance);
  }
}

// Runs pass_check (what `validate` runs) after `warmup_frames` CPU frames and checks each
// pass of a substep without self-collision (unfused and fused), and the normals.
inline void check_each_pass(const Scene& scene, int warmup_frames) {
  const ClothModel model = build_cloth(scene);
  GpuSimulator gpu(scene, model, compute_dir());
  const std::vector<PassError> errors = check_passes(scene, model, gpu, warmup_frames);
  std::vector<std::string> names;
  for (const PassError& e : errors) {
    names.push_back(e.pass);
    INFO(e.pass << ": max |GPU - CPU| = " << e.max_error << " m" << (e.bitwise ? " (bitwise equal)" : ""));
    if (gl::gl_renderer_is_llvmpipe()) {
      CHECK(e.max_error == 0);
      CHECK(e.bitwise);
    } else {
      CHECK(e.max_error <= kPassTolerance);
    }
  }
  // With colliders the step fuses collide_objects into advance (self-collision is off here).
  const bool colliders = !scene.spheres.empty() || !scene.planes.empty();
  // (A classic scene: fabric's passes are checked in test_gpu_multigrid.cpp.)
  REQUIRE(scene.simulation.solver == Solver::Classic);
  const std::vector<std::string> want = {"accumulate_forces", "integrate",
                                         colliders ? "advance (+ collide_objects)" : "advance", "collide_objects",
                                         "solve_length_constraints", "compute_normals"};
  CHECK(names == want);
}

// Particles a CPU pass moved, in all and in the last (partial) workgroup of a dispatch.
struct Moved {
  size_t all = 0, last_workgroup = 0;
};
inline Moved moved(const Vec4s& before, const Vec4s& after) {
  const size_t last_start = (before.size() - 1) / WORKGROUP_SIZE * WORKGROUP_SIZE;
  Moved m;
  for (size_t i = 0; i < before.size(); ++i) {
    const bool differs = std::memcmp(&before[i], &after[i], sizeof(before[i])) != 0;
    m.all += differs;
    m.last_workgroup += differs && i >= last_start;
  }
  return m;
}

// Whom each collider (spheres, then planes, in file order) and the length constraint move in
// the substep after `frames` frames on the CPU: a pass that moves nothing checks nothing.
struct Exercised {
  std::vector<Moved> by_sphere, by_plane;
  Moved constrained;
};
inline Exercised exercised(const Scene& scene, const ClothModel& model, int frames) {
  CpuBackend<float> cpu(scene, model);
  for (int f = 0; f < frames; ++f) cpu.step_frame();
  const Constants<float>& c = cpu.constants();
  State<float> s = cpu.state();
  accumulate_forces(model, c, s);
  integrate(model, c, s);
  // collide_objects with all colliders is each collider alone, one after the other.
  auto apply = [&](Constants<float> one) {
    const Vec4s before = s.pos;
    collide_objects(one, s);
    return moved(before, s.pos);
  };
  Exercised e;
  for (const auto& sphere : c.control.spheres) {
    Constants<float> one = c;
    one.control.spheres = {sphere};
    one.control.planes.clear();
    e.by_sphere.push_back(apply(one));
  }
  for (const auto& plane : c.control.planes) {
    Constants<float> one = c;
    one.control.spheres.clear();
    one.control.planes = {plane};
    e.by_plane.push_back(apply(one));
  }
  const Vec4s before = s.pos;
  solve_length_constraints(model, c, s);
  e.constrained = moved(before, s.pos);
  return e;
}

// Every collider and the length constraint move some particle in the substep after `frames`
// frames, and (with `in_last_workgroup`) some particle of the last workgroup.
inline void check_exercised(const Scene& scene, const ClothModel& model, int frames, bool in_last_workgroup) {
  const Exercised e = exercised(scene, model, frames);
  auto check = [&](const std::string& what, const Moved& m) {
    INFO(what << " moves " << m.all << " particles, " << m.last_workgroup << " of the last workgroup, in the "
              << "substep after " << frames << " frames");
    CHECK(m.all > 0);
    if (in_last_workgroup) CHECK(m.last_workgroup > 0);
  };
  for (size_t k = 0; k < e.by_sphere.size(); ++k) check(fmt::format("sphere {}", k), e.by_sphere[k]);
  for (size_t k = 0; k < e.by_plane.size(); ++k) check(fmt::format("plane {}", k), e.by_plane[k]);
  check("the length constraint", e.constrained);
}

inline void check_passes_on_grid(int nw, int nh) {
  const Scene scene = pressed_cloth(nw, nh);
  const ClothModel model = build_cloth(scene);
  INFO(nw << "x" << nh << " cloth");
  check_exercised(scene, model, kWarmupFrames, true);
  check_each_pass(scene, kWarmupFrames);
}

// The CPU reference (float) after `frames` frames of a scene: where a run is compared from.
struct CpuCloth {
  Scene scene;
  ClothModel model = build_cloth(scene);
  Constants<float> c = make_constants<float>(scene, model);
  State<float> s = initial_state<float>(model);
  int frames = 0;
  CpuCloth(Scene sc, int warmup_frames) : scene(std::move(sc)), frames(warmup_frames) {
    for (int k = 0; k < frames * int(c.steps); ++k) step(model, c, s);
  }
  void run(int substeps) {
    for (int k = 0; k < substeps; ++k) step(model, c, s);
    compute_normals(model, s);
  }
};

// GpuSimulator::step() `substeps` times, then the normals, from the CPU cloth's state (from
// the simulator's own initial upload when there was no warm-up); `cpu` does the same.
inline State<float> run_gpu(const CpuCloth& cpu, int substeps) {
  GpuSimulator gpu(cpu.scene, cpu.model, compute_dir());
  if (cpu.frames > 0) gpu.upload(cpu.s);
  for (int k = 0; k < substeps; ++k) gpu.step();
  gpu.run(PassId::compute_normals);
  State<float> g;
  gpu.download(g);
  return g;
}

inline void check_run(const Scene& scene, int warmup_frames, int substeps) {
  CpuCloth cpu(scene, warmup_frames);
  const State<float> g = run_gpu(cpu, substeps);
  cpu.run(substeps);
  check_same("positions", g.pos, cpu.s.pos, kRunTolerance);
  check_same("displacements", g.disp, cpu.s.disp, kRunTolerance);
  check_same("normals", g.normal, cpu.s.normal, kRunTolerance);
}

}  // namespace pass_fixtures
using namespace pass_fixtures;

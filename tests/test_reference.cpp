// The CPU reference against the numbers docs/design.md §1 says the model must show.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "backend.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {
// No springs, no self-collision: every particle is a lone mass.
Scene lone_masses(double damping) {
  return test::make_scene(3, 3, 0, {"cloth.enable_structural=false", "cloth.enable_shearing=false",
                                    "cloth.enable_bending=false", "simulation.self_collision=false",
                                    fmt::format("cloth.damping={}", damping)});
}
}  // namespace

TEST_CASE("a lone unpinned mass without damping falls 1/2 g t^2", "[reference]") {
  Scene s = lone_masses(0);
  ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  const int frames = 45;
  for (int f = 0; f < frames; ++f) cpu.step_frame();
  const double t = frames / s.simulation.frames_per_sec, dt = s.dt();
  const double drop = 1.0 - cpu.state().pos[4].y;
  // Verlet from rest drops g dt^2 n(n+1)/2 after n substeps: ahead of 1/2 g t^2 by 1/2 g dt t.
  CHECK(drop == Approx(0.5 * 9.8 * t * t).margin(0.5 * 9.8 * dt * t * 1.01));
  CHECK(drop > 0.5 * 9.8 * t * t * 0.999);
}

TEST_CASE("with damping a lone mass tends to the terminal speed g dt / (d/100)", "[reference]") {
  Scene s = lone_masses(0.2);
  ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (int f = 0; f < 90; ++f) cpu.step_frame();
  const auto& st = cpu.state();
  const double v = -st.disp[4].y / s.dt();  // the Verlet velocity (x - x_prev) / dt
  const double terminal = 9.8 * s.dt() / (0.2 / 100);
  CHECK(terminal == Approx(1.8148).epsilon(1e-3));
  CHECK(v == Approx(terminal).epsilon(0.01));
}

TEST_CASE("pinned masses never move", "[reference]") {
  Scene s = test::make_scene(7, 5, 0, {"cloth.pinned=[[0,0],[6,0],[3,2]]"},
                             R"(, "sphere": {"origin": [0.5, 0.5, 0.5], "radius": 0.3, "friction": 0.3})");
  ClothModel m = build_cloth(s);
  CpuBackend<float> cpu(s, m);
  const auto before = cpu.state().pos;
  for (int f = 0; f < 30; ++f) cpu.step_frame();
  for (int i : {m.index(0, 0), m.index(6, 0), m.index(3, 2)}) {
    CHECK(cpu.state().pos[i] == before[i]);  // bitwise
    CHECK(cpu.state().disp[i] == Vec4<float>(0));  // never any velocity
  }
}

TEST_CASE("with enough constraint iterations no spring exceeds (1 + max_stretch) L after a substep",
          "[reference]") {
  Scene s = test::make_scene(9, 7, 0, {"cloth.pinned=[[0,0],[8,0]]", "cloth.ks=20",
                                       "simulation.constraint_iterations=200", "simulation.self_collision=false"});
  ClothModel m = build_cloth(s);
  auto c = make_constants<double>(s, m);
  auto st = initial_state<double>(m);
  double worst = 0;
  for (int k = 0; k < 300; ++k) {
    step(m, c, st);
    for (const Spring& sp : m.springs)
      worst = std::max(worst, glm::length(glm::dvec3(st.pos[sp.j]) - glm::dvec3(st.pos[sp.i])) / sp.rest);
  }
  INFO("worst stretch ratio " << worst);
  CHECK(worst <= 1.1 + 1e-6);
  CHECK(worst > 1.05);  // soft springs really did stretch the cloth up to the limit
}

TEST_CASE("no mass ends inside a sphere", "[reference]") {
  Scene s = test::make_scene(15, 15, 0, {"simulation.self_collision=false"},
                             R"(, "sphere": {"origin": [0.5, 0.5, 0.5], "radius": 0.25, "friction": 0.3})");
  ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  double worst = 1;
  for (int f = 0; f < 120; ++f) {
    cpu.step_frame();
    worst = std::min(worst, measure(s, m, cpu.snapshot()).sphere_clearance[0]);
  }
  INFO("deepest penetration " << -worst << " m");
  // The friction blend moves along a chord and the length constraint runs after the
  // projection, so masses may end slightly inside: at most 0.5 mm here.
  CHECK(worst > -5e-4);
  CHECK(worst < 0.01);  // the cloth really lies on the sphere
}

TEST_CASE("no mass ends across a plane, whichever way its normal points", "[reference]") {
  for (const char* normal : {"[0, 1, 0]", "[0, -1, 0]"}) {
    Scene s = test::make_scene(
        11, 11, 0, {"simulation.self_collision=false"},
        fmt::format(R"(, "plane": {{"point": [0, 0.3, 0], "normal": {}, "friction": 0.5}})", normal));
    ClothModel m = build_cloth(s);
    CpuBackend<double> cpu(s, m);
    double lowest = 1;
    for (int f = 0; f < 150; ++f) {
      cpu.step_frame();
      for (auto& p : cpu.state().pos) lowest = std::min(lowest, p.y - 0.3);
    }
    INFO("normal " << normal << ", lowest mass " << lowest << " m above the plane");
    CHECK(lowest >= 0);
    CHECK(lowest < 0.01);  // it really reached the plane
  }
}

TEST_CASE("with damping and no collisions total energy does not grow", "[reference]") {
  // Zero gravity, nothing pinned, no colliders, and a length limit the springs never reach:
  // the only energy is the springs' (the cloth starts stretched 10 % about its centre) and the
  // motion it turns into, and damping may only take it away. Verlet's discrete energy (the
  // velocity d / dt lags half a substep) wobbles a little from frame to frame.
  Scene s = test::make_scene(9, 7, 0, {"simulation.self_collision=false", "simulation.gravity=[0,0,0]",
                                       "simulation.max_stretch=10"});
  ClothModel m = build_cloth(s);
  CpuBackend<double> cpu(s, m);
  for (auto& p : cpu.state().pos) p = glm::dvec4(glm::dvec3(0.5, 1, 0.5) + (glm::dvec3(p) - glm::dvec3(0.5, 1, 0.5)) * 1.1, p.w);
  const double start = measure(s, m, cpu.snapshot()).total_energy();
  REQUIRE(start > 1.0);  // J: the stretch is really there
  constexpr double kWobble = 1e-3;  // of the starting energy, from one frame to the next
  double previous = start, worst_rise = -INFINITY;
  for (int f = 0; f < 180; ++f) {
    cpu.step_frame();
    const double e = measure(s, m, cpu.snapshot()).total_energy();
    worst_rise = std::max(worst_rise, (e - previous) / start);
    previous = e;
  }
  INFO("energy start " << start << " J, end " << previous << " J, largest rise between frames " << worst_rise
                       << " of the start");
  CHECK(worst_rise <= kWobble);
  CHECK(previous < 0.5 * start);  // it really oscillated and lost energy
}

TEST_CASE("float and double references agree to float32 precision over one frame", "[reference]") {
  Scene s = test::make_scene(9, 7, 0, {"cloth.pinned=[[0,0],[8,0]]"});
  ClothModel m = build_cloth(s);
  CpuBackend<float> f32(s, m);
  CpuBackend<double> f64(s, m);
  f32.step_frame();
  f64.step_frame();
  // Over whole runs float32 drifts by millimetres (README "Precision"); one frame of 30
  // substeps must stay at the level of a few hundred ULPs of a 1 m coordinate.
  const double d = test::max_abs_diff(f32.snapshot().pos, f64.snapshot().pos);
  INFO("float - double after 1 frame: " << d << " m");
  CHECK(d < 5e-5);
}

TEST_CASE("normals of a flat horizontal cloth point up", "[reference]") {
  Scene s = test::make_scene(7, 5, 0);
  ClothModel m = build_cloth(s);
  auto st = initial_state<double>(m);
  compute_normals(m, st);
  for (auto& n : st.normal) CHECK(glm::dvec3(n) == glm::dvec3(0, 1, 0));
}

// simulation.max_speed (the speed clamp): the integration moves no free mass further than
// max_speed * dt per substep, so a dropped cloth's centre of mass never outruns it, where it
// reaches 9.8 m/s after a second of free fall without the clamp.
TEST_CASE("with simulation.max_speed 2 a dropped cloth never falls faster than 2 m/s", "[reference]") {
  for (const char* solver : {"classic", "fabric"}) {
    for (const double max_speed : {0.0, 2.0}) {
      Scene s = test::make_scene(9, 9, 0, {"simulation.self_collision=false", "cloth.damping=0",
                                           fmt::format("simulation.solver=\"{}\"", solver),
                                           fmt::format("simulation.max_speed={}", max_speed)});
      ClothModel m = build_cloth(s);
      CpuBackend<double> cpu(s, m);
      auto centre = [&] {  // of mass: the springs' pulls cancel in it
        glm::dvec3 sum(0);
        double mass = 0;
        for (const auto& p : cpu.state().pos) sum += glm::dvec3(p) / p.w, mass += 1.0 / p.w;
        return sum / mass;
      };
      double fastest = 0;
      glm::dvec3 last = centre();
      for (int f = 0; f < 90; ++f) {
        cpu.step_frame();
        const glm::dvec3 now = centre();
        fastest = std::max(fastest, glm::length(now - last) * s.simulation.frames_per_sec);
        last = now;
      }
      INFO(solver << ", max_speed " << max_speed << ": fastest " << fastest << " m/s");
      if (max_speed > 0)
        CHECK(fastest <= max_speed * (1 + 1e-9));
      else
        CHECK(fastest > 9.0);
    }
  }
}

// The limit_speed pass at the end of every substep: no free mass's move over a substep is
// longer than max_speed * dt, whatever the constraints and the contacts did after the
// integration (here a sphere the cloth falls onto, and pins that hold it at two corners).
TEST_CASE("with simulation.max_speed no free mass moves faster than max_speed over any substep", "[reference]") {
  for (const char* solver : {"classic", "fabric"}) {
    Scene s = test::make_scene(17, 17, 0, {"cloth.damping=0", "cloth.pinned=[[0,0],[16,0]]",
                                           fmt::format("simulation.solver=\"{}\"", solver), "simulation.max_speed=1.5"},
                               R"(, "sphere": {"origin": [0.5, 0.2, 0.5], "radius": 0.5, "friction": 0.3})");
    ClothModel m = build_cloth(s);
    CpuBackend<double> cpu(s, m);
    const double max_move = 1.5 * s.dt();
    double longest = 0;
    for (int f = 0; f < 60; ++f) {
      cpu.step_frame();
      for (int i = 0; i < m.count(); ++i)
        if (cpu.state().pos[i].w != 0) longest = std::max(longest, glm::length(glm::dvec3(cpu.state().disp[i])));
    }
    INFO(solver << ": longest move " << longest << " m, max_speed * dt " << max_move << " m");
    CHECK(longest <= max_move * (1 + 1e-9));
    CHECK(longest > 0.5 * max_move);  // it does fall
  }
}

#include "pass_check.hpp"

#include <cmath>
#include <functional>

namespace clothsim {

std::vector<PassError> check_passes(const Scene& scene, const ClothModel& model, GpuSimulator& gpu, int warmup) {
  CpuBackend<float> cpu(scene, model);
  for (int f = 0; f < warmup; ++f) cpu.step_frame();
  const Constants<float>& c = cpu.constants();
  State<float>& s = cpu.state();
  State<float> g;
  std::vector<PassError> out;

  // Runs one pass on both sides from the CPU's current state; leaves the CPU after the pass.
  auto check = [&](const char* name, const std::function<void()>& on_cpu, const std::function<void()>& on_gpu,
                   auto stream) {
    gpu.upload(s);
    on_cpu();
    on_gpu();
    gpu.download(g);
    Deviation d = deviation(stream(g), stream(s));
    out.push_back({name, d.max, d.bitwise});
  };
  auto positions = [](const State<float>& st) { return st.pos; };
  auto both = [](const State<float>& st) {
    auto v = st.pos;
    v.insert(v.end(), st.prev.begin(), st.prev.end());
    return v;
  };
  // A force error matters by the displacement it causes in one substep: F * w * dt^2.
  auto displacement = [&](const State<float>& st) {
    std::vector<Vec4<float>> v(st.force.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = st.force[i] * (s.pos[i].w * c.dt2);
    return v;
  };
  // The unfused passes, then (from the same state) the fused ones GpuSimulator::step runs:
  // collide_objects rides along with advance, or with collide_self when that is on.
  const State<float> start = s;
  check("accumulate_forces", [&] { accumulate_forces(model, c, s); }, [&] { gpu.accumulate_forces(); }, displacement);
  check("integrate", [&] { integrate(c, s); }, [&] { gpu.integrate(); }, both);
  s = start;
  const bool colliders = c.has_colliders();
  const bool objects_in_advance = colliders && !c.self_collision;
  check(objects_in_advance ? "advance (+ collide_objects)" : "advance",
        [&] {
          advance(model, c, s);
          if (objects_in_advance) collide_objects(c, s);
        },
        [&] { gpu.advance(objects_in_advance); }, both);
  if (c.self_collision) {
    const State<float> before = s;
    check("collide_self", [&] { collide_self(c, s); }, [&] { gpu.collide_self(); }, positions);
    if (colliders) {
      s = before;
      check("collide_self (+ collide_objects)",
            [&] {
              collide_self(c, s);
              collide_objects(c, s);
            },
            [&] { gpu.collide_self(true); }, positions);
    }
  }
  check("collide_objects", [&] { collide_objects(c, s); }, [&] { gpu.collide_objects(); }, positions);
  check("solve_length_constraints", [&] { solve_length_constraints(model, c, s); },
        [&] { gpu.solve_length_constraints(); }, positions);
  check("compute_normals", [&] { compute_normals(model, s); }, [&] { gpu.compute_normals(); },
        [](const State<float>& st) { return st.normal; });
  return out;
}

}  // namespace clothsim

// Collider contact cases shared by the CPU tests and their GPU twins (docs/model.md,
// "Colliders"): a mass found behind a plane, a mass that passed through a static sphere and one
// that a fast sphere passed over within the substep, each set up as a state on a 3x3 cloth.
#pragma once

#include "reference/reference.hpp"
#include "test_helpers.hpp"

namespace clothsim::test {

// A plane at y = 0.5 (the cloth, at y = 1, in front of it), a static sphere at (0.5, 0.8, 0.5)
// and a fast one of radius 0.05 moving at 810 m/s along -z, from (0.2, 0.8, 0.5) at t = 0 to
// (0.2, 0.8, 0.2) at the end of the first substep (dt = 1/2700 s), all frictionless.
inline Scene contact_scene() {
  return make_scene(3, 3, 0, {"simulation.self_collision=false"}, R"(,
    "sphere": [{"origin": [0.5, 0.8, 0.5], "radius": 0.05, "friction": 0.0},
               {"origin": [0.2, 0.8, 0.2], "radius": 0.05, "friction": 0.0,
                "motion": {"keyframes": [[0, [0.2, 0.8, 0.5]], [1, [0.2, 0.8, -809.5]]]}}],
    "plane": {"point": [0, 0.5, 0], "normal": [0, 1, 0], "friction": 0.0})");
}

// Particle 0: below the plane at both ends of the substep (x_prev = 0.491, x = 0.49).
// Particle 1: fell through the static sphere this substep (from y 0.9 to 0.7 straight through
// its centre). Particle 2: stood still at (0.23, 0.8, 0.3) while the fast sphere swept over it
// (outside it at both ends, 3 cm off its path's axis). The rest are far from everything.
template <class R> void set_contact_state(State<R>& s) {
  for (auto& p : s.pos) p = Vec4<R>(p.x, R(1.3), p.z, p.w);
  for (auto& d : s.disp) d = Vec4<R>(0);
  s.pos[0] = Vec4<R>(R(0.1), R(0.49), R(0.1), s.pos[0].w);
  s.disp[0] = Vec4<R>(R(0.0), R(-0.001), R(0.0), R(0));
  s.pos[1] = Vec4<R>(R(0.5), R(0.7), R(0.5), s.pos[1].w);
  s.disp[1] = Vec4<R>(R(0.0), R(-0.2), R(0.0), R(0));
  s.pos[2] = Vec4<R>(R(0.23), R(0.8), R(0.3), s.pos[2].w);
}

// A horizontal 17x11 cloth hung from its (0, 0) corner, pinned behind a vertical plane
// through the cloth near that corner, with gravity leaning towards the plane: the cloth presses
// on it, the masses that start behind it are found behind (the CS184 blend, from x_prev, leaves
// them behind), and the springs from the pin are stretched past max_stretch, so Provot pulls
// their far ends towards the pin, through the plane.
inline Scene pin_behind_plane_scene(std::vector<std::string> sets = {}) {
  sets.insert(sets.end(), {"cloth.pinned=[[0,0]]", "simulation.gravity=[-4.0, -9.8, -4.0]"});
  return make_scene(17, 11, 0, sets,
                    R"(, "plane": {"point": [0.12, 1.0, 0.12], "normal": [1.0, 0.0, 1.0], "friction": 0.3})");
}

}  // namespace clothsim::test

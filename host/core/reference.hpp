// The CPU reference: DESIGN.md §1, one function per pass, named like the compute shader
// that mirrors it. Templated on the scalar so the same code runs in float (compared with
// the GPU bit for bit on llvmpipe) and in double (the noise floor of a float32 run).
// Every expression is written in the same operation order as its GLSL twin.
#pragma once

#include <cmath>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cloth.hpp"
#include "scene.hpp"
#include "spatial_hash.hpp"

namespace clothsim {

template <class R> using Vec3 = glm::vec<3, R>;
template <class R> using Vec4 = glm::vec<4, R>;

// |v| summed as (x*x + y*y) + z*z, the order the shaders use (compute/common.glsl).
template <class R> R length3(const Vec3<R>& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
template <class R> R dot3(const Vec3<R>& a, const Vec3<R>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

template <class R> struct SphereC { Vec3<R> origin; R radius; R keep; };  // keep = 1 - friction
template <class R> struct PlaneC { Vec3<R> point; Vec3<R> normal; R keep; };

// Scene parameters converted once to R: the GPU uploads exactly Constants<float>.
template <class R> struct Constants {
  Vec3<R> gravity;
  R mass, ks, ks_bending, keep_velocity, dt2;
  R stretch_limit;      // 1 + max_stretch
  R contact_distance;   // 2 * thickness
  R inv_cell;           // 1 / cell edge (cell edge = 2 * thickness)
  R steps;              // simulation_steps
  // xpbd: the time-scaled compliance alpha~ = 1 / (ks' dt^2) of a spring's distance constraint.
  R alpha, alpha_bending;
  R tether_limit;       // xpbd: 1 + tether_stretch
  bool enabled[3];      // by SpringType
  int iterations;
  bool self_collision;
  bool xpbd;            // simulation.solver
  std::vector<SphereC<R>> spheres;
  std::vector<PlaneC<R>> planes;
  bool has_colliders() const { return !spheres.empty() || !planes.empty(); }
};

template <class R> Constants<R> make_constants(const Scene& scene, const ClothModel& model);

// What changes during a run: positions (w = inverse mass, 0 = pinned), the displacement of
// the last substep (d = x - x_prev, w unused), forces and normals, all vec4 like the GPU
// buffers. The displacement is kept as its own vector rather than recomputed from two
// positions: x - x_prev of two floats near 1 m would round the ~1e-5 m velocity term by ~1 %
// every substep (docs/model.md, "State"). Every change of a position is added to both.
template <class R> struct State {
  std::vector<Vec4<R>> pos, disp, force, normal;
  SpatialHash hash;                 // self-collision scratch, sized once
  std::vector<Vec4<R>> pos_out;     // self-collision Jacobi output
};

template <class R> State<R> initial_state(const ClothModel& model);

// After a change of the substep length (frames_per_sec or simulation_steps), the displacement
// per substep scales with it, so the cloth keeps its velocity: d *= dt_new / dt_old.
template <class R> void rescale_displacement(State<R>& s, double dt_ratio) {
  for (auto& d : s.disp) d = Vec4<R>(Vec3<R>(d) * R(dt_ratio), R(0));
}

// The passes, in step order.
template <class R> void accumulate_forces(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void integrate(const Constants<R>& c, State<R>& s);
// Builds the hash (count_cells, scan_cells, fill_cells, sort_cells in spatial_hash.hpp), then
// resolve_self_contacts: the stages the GPU runs as five passes of the same names.
template <class R> void collide_self(const Constants<R>& c, State<R>& s);
template <class R> void resolve_self_contacts(const Constants<R>& c, State<R>& s);  // on s.hash as built
template <class R> void collide_objects(const Constants<R>& c, State<R>& s);
template <class R> void solve_length_constraints(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void compute_normals(const ClothModel& m, State<R>& s);

// Forces then integrate: the CPU twin of the GPU's fused advance pass (which keeps the
// forces in registers; with collision objects fused in it is advance then collide_objects).
// accumulate_forces and integrate on their own are twins of passes the GPU keeps only for
// the pass checks (host/gpu/pass_check.cpp); its step runs advance.
template <class R> void advance(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  accumulate_forces(m, c, s);
  integrate(c, s);
}

// One constraint colour (used by the per-pass check that dispatches colours one by one).
template <class R> void solve_length_constraint_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s);

// The xpbd solver (docs/model.md): predict moves every free particle by its damped
// displacement and gravity alone (the springs are constraints now), then pulls it back onto
// its tether to the nearest pin if it got further than (1 + tether_stretch) times the rest
// distance (long-range attachments, tethers.cpp); solve_distance_constraints
// then solves each spring's XPBD distance constraint once, colour by colour, each followed by
// the max_stretch limit in the same spring's visit.
template <class R> void predict(const ClothModel& m, const Constants<R>& c, State<R>& s);
template <class R> void solve_distance_constraint_colour(const ClothModel& m, const Constants<R>& c, int colour, State<R>& s);
template <class R> void solve_distance_constraints(const ClothModel& m, const Constants<R>& c, State<R>& s);

// One substep: the pass list of DESIGN.md §1, or of docs/model.md for xpbd.
template <class R> void step(const ClothModel& m, const Constants<R>& c, State<R>& s) {
  if (c.xpbd) {
    predict(m, c, s);
    if (c.self_collision) collide_self(c, s);
    collide_objects(c, s);
    solve_distance_constraints(m, c, s);
    return;
  }
  advance(m, c, s);
  if (c.self_collision) collide_self(c, s);
  collide_objects(c, s);
  solve_length_constraints(m, c, s);
}

}  // namespace clothsim

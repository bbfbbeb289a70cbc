// Living scenes on both backends: wind (aerodynamic drag and lift per triangle), keyframed
// colliders and moving pins. The CPU reference (float) and the GPU run the same scene; each
// property is checked on both. Untagged cases are CPU only.
#include <cmath>
#include <functional>

#include "gpu_pass_fixtures.hpp"
#include "scene/motion.hpp"

namespace {

using pass_fixtures::compute_dir;

// Runs `frames` frames on the float reference and, when a GL context exists, on the GPU,
// calling `each(backend, frame, state)` after every frame.
using FrameCheck = std::function<void(const char* backend, int frame, const State<float>& s)>;
void run_cpu(const Scene& scene, const ClothModel& model, int frames, const FrameCheck& each) {
  CpuBackend<float> cpu(scene, model);
  for (int f = 1; f <= frames; ++f) {
    cpu.step_frame();
    each("cpu", f, cpu.state());
  }
}
void run_gpu(const Scene& scene, const ClothModel& model, int frames, const FrameCheck& each) {
  GpuSimulator gpu(scene, model, compute_dir());
  State<float> s;
  for (int f = 1; f <= frames; ++f) {
    gpu.step_frame();
    gpu.download(s);
    each("gpu", f, s);
  }
}

glm::dvec3 mean_position(const State<float>& s) {
  glm::dvec3 sum(0.0);
  for (auto& p : s.pos) sum += glm::dvec3(p);
  return sum / double(s.pos.size());
}
double mean_distance(const State<float>& a, const State<float>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pos.size(); ++i) sum += glm::length(glm::dvec3(a.pos[i]) - glm::dvec3(b.pos[i]));
  return sum / double(a.pos.size());
}

// A vertical 33x33 cloth (the x-y plane) pinned along its x = 0 edge, no gravity, a light
// fabric (15 kg/m^2, a tenth of the classic density, so 1 s shows the wind).
Scene side_pinned(const std::string& wind) {
  std::string pins;
  for (int y = 0; y < 33; ++y) pins += fmt::format("{}[0,{}]", y ? "," : "", y);
  return test::make_scene(33, 33, 1,
                          {"cloth.pinned=[" + pins + "]", "cloth.density=15", "simulation.gravity=[0,0,0]",
                           "simulation.self_collision=false"},
                          wind.empty() ? "" : ", \"wind\": " + wind);
}

// Mean position after 1 s (90 frames) on one backend.
State<float> after_one_second(const Scene& scene, const ClothModel& model, bool gpu) {
  State<float> last;
  auto keep = [&](const char*, int, const State<float>& s) { last = s; };
  (gpu ? run_gpu : run_cpu)(scene, model, 90, keep);
  return last;
}

void check_wind_moves_the_cloth(bool gpu) {
  const Scene still = side_pinned(""), across = side_pinned(R"({"velocity": [0, 0, 5]})"),
              along = side_pinned(R"({"velocity": [5, 0, 0]})");
  const ClothModel model = build_cloth(still);
  const State<float> start = initial_state<float>(model);
  const State<float> s_across = after_one_second(across, model, gpu);
  const State<float> s_along = after_one_second(along, model, gpu);
  const State<float> s_still = after_one_second(still, model, gpu);
  const double dz = mean_position(s_across).z - mean_position(start).z;
  const double moved_across = mean_distance(s_across, start), moved_along = mean_distance(s_along, start);
  const double moved_still = mean_distance(s_still, start);
  INFO((gpu ? "gpu" : "cpu") << ": mean z moved " << dz << " m downwind; mean move across " << moved_across
                             << " m, along " << moved_along << " m, still " << moved_still << " m");
  CHECK(dz >= 0.05);
  CHECK(moved_along < 0.1 * moved_across);
  CHECK(moved_still < 1e-6);
}

}  // namespace

TEST_CASE("a wind across a cloth pinned along one edge blows it downwind and one along it barely moves it", "[long]") {
  check_wind_moves_the_cloth(false);
}

TEST_CASE("a wind across a cloth pinned along one edge blows it downwind on the GPU and one along it barely moves it", "[gpu][long]") {
  REQUIRE_GL_CONTEXT();
  check_wind_moves_the_cloth(true);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the wind force has the formulas' magnitudes on a single flat triangle pair") {
  // A 2x2 cloth (one cell, two triangles) at rest, facing a 5 m/s wind head on: the drag on
  // the whole cloth is 1/2 rho C_d A |v|^2, along the wind; lift is 0 (v along n).
  const Scene scene = test::make_scene(2, 2, 0, {"simulation.gravity=[0,0,0]", "simulation.self_collision=false"},
                                       R"(, "wind": {"velocity": [0, 5, 0], "lift_coefficient": 0.7})");
  const ClothModel model = build_cloth(scene);
  const Constants<double> c = make_constants<double>(scene, model);
  State<double> s = initial_state<double>(model);
  compute_wind_forces(model, c, s);
  glm::dvec3 total(0.0);
  for (auto& f : s.wind) total += glm::dvec3(f);
  const double want = 0.5 * 1.225 * 1.2 * 1.0 * 25.0;
  CHECK(total.y == Approx(want).epsilon(1e-12));
  CHECK(std::abs(total.x) < 1e-12);
  CHECK(std::abs(total.z) < 1e-12);
}

namespace {

// The wind's total force on a still, flat, horizontal 7x5 cloth (1 m x 1 m, normal +-y) at rest,
// with the air blowing at `degrees` to the cloth's plane in the x-y plane: the sum of
// compute_wind_forces over all particles (every triangle's force is split into thirds at its
// corners), on the double reference or on the GPU.
struct WindCase {
  double degrees, speed, drag, lift;
};
glm::dvec3 wind_direction(double degrees) {
  const double a = degrees * M_PI / 180.0;
  return {std::cos(a), std::sin(a), 0.0};
}
glm::dvec3 total_wind_force(const WindCase& w, bool gpu) {
  const glm::dvec3 v = w.speed * wind_direction(w.degrees);
  const Scene scene = test::make_scene(
      7, 5, 0, {"simulation.gravity=[0,0,0]", "simulation.self_collision=false"},
      fmt::format(R"(, "wind": {{"velocity": [{:.17g}, {:.17g}, 0], "drag_coefficient": {}, "lift_coefficient": {}}})",
                  v.x, v.y, w.drag, w.lift));
  const ClothModel model = build_cloth(scene);
  glm::dvec3 total(0.0);
  if (gpu) {
    GpuSimulator sim(scene, model, compute_dir());
    sim.run(PassId::compute_wind_forces);
    State<float> s;
    sim.download(s);
    for (auto& f : s.wind) total += glm::dvec3(f);
  } else {
    const Constants<double> c = make_constants<double>(scene, model);
    State<double> s = initial_state<double>(model);
    compute_wind_forces(model, c, s);
    for (auto& f : s.wind) total += glm::dvec3(f);
  }
  return total;
}

// The model (docs/model.md, "Wind"), with the cloth still: v = -v_air relative to the air, and
// with theta the angle between v and the normal, cos(theta) = |v_hat . n| = sin(angle to the
// plane). Drag -1/2 rho C_d A |v| (v.n) n lies along the normal: 1/2 rho C_d A |v|^2 cos^2(theta)
// along the wind and 1/2 rho C_d A |v|^2 cos(theta) sin(theta) across it. Lift
// -1/2 rho C_l A (v.n) (|v| n - (v.n)/|v| v) is across the wind only, of size
// 1/2 rho C_l A |v|^2 cos(theta) sin(theta), on the side the normal leans to from the wind
// (here +y: the air rising through the cloth lifts it). Neither depends on which way n points.
void check_wind_components(bool gpu) {
  const double rho = 1.225, area = 1.0;
  // Relative tolerance: double rounding on the reference, float (35 corners summed) on the GPU.
  const double tol = gpu ? 1e-4 : 1e-9;
  for (const WindCase w : {WindCase{30, 5, 0.0, 0.7}, WindCase{30, 5, 1.2, 0.7}, WindCase{30, 5, 1.2, 0.0},
                           WindCase{20, 8, 0.0, 0.4}, WindCase{20, 8, 0.9, 0.4}}) {
    const glm::dvec3 along_dir = wind_direction(w.degrees);
    const glm::dvec3 across_dir = wind_direction(w.degrees + 90);  // in the plane of v and n, +y side
    const double cos_t = std::sin(w.degrees * M_PI / 180.0), sin_t = std::cos(w.degrees * M_PI / 180.0);
    REQUIRE(cos_t * sin_t > 0.3);  // neither head on (sin 0) nor edge on (cos 0)
    const double q = 0.5 * rho * area * w.speed * w.speed;
    const double want_along = q * w.drag * cos_t * cos_t;
    const double want_lift = q * w.lift * cos_t * sin_t;
    const double want_drag_across = q * w.drag * cos_t * sin_t;

    const glm::dvec3 f = total_wind_force(w, gpu);
    const double along = glm::dot(f, along_dir), across = glm::dot(f, across_dir);
    INFO((gpu ? "gpu" : "cpu") << ": wind at " << w.degrees << " deg to the cloth, " << w.speed << " m/s, C_d "
                               << w.drag << ", C_l " << w.lift << ": force (" << f.x << ", " << f.y << ", " << f.z
                               << "), along the wind " << along << " (want " << want_along << "), across "
                               << across << " (want lift " << want_lift << " + drag " << want_drag_across << ")");
    const double scale = q;  // the size of every force here
    CHECK(std::abs(f.z) < tol * scale);  // nothing out of the plane of the wind and the normal
    CHECK(along == Approx(want_along).margin(tol * scale));
    CHECK(across - want_drag_across == Approx(want_lift).epsilon(tol).margin(tol * scale));
    if (w.drag == 0) {
      // Lift alone: all of it across the wind, the model's size within 1 % (here: to rounding).
      CHECK(std::abs(along) < tol * scale);
      CHECK(across == Approx(want_lift).epsilon(std::min(0.01, tol)));
      CHECK(across > 0.1 * q);
    }
  }
}

}  // namespace

TEST_CASE("a wind at an angle to a still flat cloth has the model's lift across it and drag along it") {
  check_wind_components(false);
}

TEST_CASE("a wind at an angle to a still flat cloth has the model's lift and drag on the GPU", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_wind_components(true);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("gusts repeat every gust length along the wind and swing the other way half a length on") {
  CHECK(gust_phase(5.0, 2.0) == 0.5);
  // Two cloths a gust length apart along the wind see the same wind; half a length, the opposite swing.
  const char* wind = R"(, "wind": {"velocity": [0, 4, 0], "gust": {"strength": 0.5, "period": 1, "length": 2}})";
  auto force_at = [&](double y_offset_tenths) {
    Scene scene = test::make_scene(2, 2, 0, {"simulation.gravity=[0,0,0]"}, wind);
    const ClothModel model = build_cloth(scene);
    Constants<double> c = make_constants<double>(scene, model);
    set_substep_time(c, 0.25);  // a quarter period in: the wave is not at a zero
    State<double> s = initial_state<double>(model);
    for (auto& p : s.pos) p.y += y_offset_tenths;
    compute_wind_forces(model, c, s);
    double sum = 0;
    for (auto& f : s.wind) sum += f.y;
    return sum;
  };
  CHECK(force_at(0.0) == Approx(force_at(2.0)).epsilon(1e-9));
  CHECK(force_at(0.0) != Approx(force_at(1.0)).epsilon(1e-3));
}

TEST_CASE("keyframes interpolate linearly and hold before the first and after the last key") {
  const Keyframes keys = {{0.5, {1, 0, 0}}, {1.5, {3, 2, 0}}};
  CHECK(interpolate(keys, 0.0) == glm::dvec3(1, 0, 0));
  CHECK(interpolate(keys, 1.0) == glm::dvec3(2, 1, 0));
  CHECK(interpolate(keys, 9.0) == glm::dvec3(3, 2, 0));
}

namespace {

// A vertical 33x33 cloth hanging from its top row; a sphere of radius 0.2 keyframed from
// z = -0.5 to z = +0.5 through it in 1 s at mid-height (and held there after).
Scene sphere_through(bool moving) {
  const std::string motion = moving ? R"(, "motion": {"keyframes": [[0, [0.5, 0.5, -0.5]], [1, [0.5, 0.5, 0.5]]]})" : "";
  return test::make_scene(33, 33, 1, {test::pin_row(33, 32), "simulation.self_collision=false"},
                          R"(, "sphere": {"origin": [0.5, 0.5, -0.5], "radius": 0.2, "friction": 0.3)" + motion + "}");
}

void check_sphere_pushes(bool gpu) {
  const Scene moving = sphere_through(true), fixed = sphere_through(false);
  const ClothModel model = build_cloth(moving);
  const State<float> a = after_one_second(moving, model, gpu), b = after_one_second(fixed, model, gpu);
  double deepest = 0;
  const glm::dvec3 o(0.5, 0.5, 0.5);
  for (auto& p : a.pos) deepest = std::max(deepest, 0.2 - glm::length(glm::dvec3(p) - o));
  const glm::dvec3 shift = mean_position(a) - mean_position(b);
  INFO((gpu ? "gpu" : "cpu") << ": mean position against the static sphere moved by (" << shift.x << ", "
                             << shift.y << ", " << shift.z << ") m; deepest mass inside the sphere " << deepest << " m");
  CHECK(shift.z > 0.05);
  CHECK(deepest <= 1e-3);
}

}  // namespace

TEST_CASE("a keyframed sphere pushed through a hanging cloth moves it and leaves no mass inside") {
  check_sphere_pushes(false);
}

TEST_CASE("a keyframed sphere pushed through a hanging cloth moves it and leaves no mass inside on the GPU", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_sphere_pushes(true);
  CHECK_NO_GL_ERRORS();
}

namespace {

void check_pins_follow(bool gpu) {
  const Scene scene = test::make_scene(
      33, 17, 0, {"cloth.pinned=[[0,0],[32,0],[16,8]]", "simulation.self_collision=false"},
      "");
  Scene moving = scene;
  moving.cloth.pinned_motion = MotionParams{{{0.0, {0, 0, 0}}, {0.2, {0.1, 0.3, 0}}, {0.4, {-0.2, 0.1, 0.25}}}};
  const ClothModel model = build_cloth(moving);
  const std::vector<int> pins = {model.index(0, 0), model.index(32, 0), model.index(16, 8)};
  double worst = 0;
  int free_moved = 0;
  auto each = [&](const char*, int frame, const State<float>& s) {
    const glm::dvec3 offset = interpolate(moving.cloth.pinned_motion->keyframes, frame / 90.0);
    for (int i : pins) worst = std::max(worst, glm::length(glm::dvec3(s.pos[i]) - (model.initial[i] + offset)));
    free_moved += s.pos[1].y != float(model.initial[1].y);
  };
  (gpu ? run_gpu : run_cpu)(moving, model, 45, each);
  INFO((gpu ? "gpu" : "cpu") << ": largest distance of a pinned mass from start + offset " << worst << " m");
  CHECK(worst <= 1e-6);
  CHECK(free_moved > 0);
}

}  // namespace

TEST_CASE("with pinned_motion every pinned mass is at its start plus the interpolated offset at every frame") {
  check_pins_follow(false);
}

TEST_CASE("with pinned_motion every pinned mass is at its start plus the offset at every GPU frame", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_pins_follow(true);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a mass resting on a plane that slides sideways is carried along by friction 1 and not by friction 0") {
  auto carried = [](double friction) {
    Scene scene = test::make_scene(
        3, 3, 0, {"simulation.self_collision=false", "cloth.ks=0"},
        fmt::format(R"(, "plane": {{"point": [0, 0.9999, 0], "normal": [0, 1, 0], "friction": {},
                         "motion": {{"keyframes": [[0, [0, 0.9999, 0]], [1, [1, 0.9999, 0]]]}}}})", friction));
    const ClothModel model = build_cloth(scene);
    CpuBackend<double> cpu(scene, model);
    for (int f = 0; f < 45; ++f) cpu.step_frame();
    return cpu.state().pos[4].x - model.initial[4].x;
  };
  const double with = carried(1.0), without = carried(0.0);
  INFO("carried " << with << " m with friction 1, " << without << " m with friction 0 (the plane moved 0.5 m)");
  CHECK(with == Approx(0.5).margin(0.02));
  CHECK(std::abs(without) < 1e-9);
}

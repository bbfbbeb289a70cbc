// libFuzzer target for the scene loader: scene JSON plus `--set` overrides.
//
// Input bytes: the scene JSON text up to the first NUL byte (the whole input if there is
// none); after it, one override ("key.path=value", as given to --set) per line ('\n' or NUL
// separated, empty lines skipped). Each input is passed to
// clothsim::parse_scene(json, "<fuzz>", overrides).
//
// Property: parse_scene either returns a Scene that is fully valid (every double finite, at
// least 2 points each way, sizes > 0, friction in [0, 1], damping in [0, 100], unit plane
// normals, pins inside the grid, at most kMaxParticles particles, ...) and that
// scene_to_json writes out and loads back bit for bit, or throws clothsim::SceneError naming
// the source. Anything else (another exception, a violated property) calls abort(), which
// libFuzzer reports as a crash; ASan/UBSan reports, hangs (-timeout) and OOMs are crashes too.
//
// The same code is built without libFuzzer into clothsim_fuzz_scene_replay (replay_main.cpp),
// which ctest runs over tests/fuzz/regressions/ and the seed corpus in every build.
#include "fuzz_scene.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>
#include <vector>

#include "scene.hpp"

namespace clothsim::fuzz {
namespace {

[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "fuzz_scene: PROPERTY VIOLATED: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void expect(bool ok, const char* what) {
  if (!ok) violated(what);
}

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool in01(double x) { return std::isfinite(x) && x >= 0 && x <= 1; }

void check_valid(const Scene& s) {
  const ClothParams& c = s.cloth;
  expect(s.source == "<fuzz>", "Scene::source is the source given");
  expect(std::isfinite(c.width) && c.width > 0, "cloth.width finite and > 0");
  expect(std::isfinite(c.height) && c.height > 0, "cloth.height finite and > 0");
  expect(std::isfinite(c.thickness) && c.thickness > 0, "cloth.thickness finite and > 0");
  expect(c.num_width_points >= 2 && c.num_height_points >= 2, "at least 2 points each way");
  const long long n = (long long)c.num_width_points * c.num_height_points;
  expect(n <= kMaxParticles, "particle count <= kMaxParticles");
  expect((long long)s.particle_count() == n, "particle_count() does not overflow");
  expect(c.orientation == Orientation::Horizontal || c.orientation == Orientation::Vertical, "orientation 0 or 1");
  for (const auto& p : c.pinned)
    expect(p[0] >= 0 && p[1] >= 0 && p[0] < c.num_width_points && p[1] < c.num_height_points, "pins inside the grid");
  expect(std::isfinite(c.damping) && c.damping >= 0 && c.damping <= 100, "cloth.damping in [0, 100]");
  expect(std::isfinite(c.density) && c.density > 0, "cloth.density finite and > 0");
  expect(std::isfinite(c.ks) && c.ks >= 0, "cloth.ks finite and >= 0");
  for (const SphereParams& sp : s.spheres) {
    expect(finite3(sp.origin), "sphere.origin finite");
    expect(std::isfinite(sp.radius) && sp.radius > 0, "sphere.radius finite and > 0");
    expect(in01(sp.friction), "sphere.friction in [0, 1]");
  }
  for (const PlaneParams& pl : s.planes) {
    expect(finite3(pl.point), "plane.point finite");
    expect(finite3(pl.normal), "plane.normal finite");
    const double len = std::sqrt(pl.normal.x * pl.normal.x + pl.normal.y * pl.normal.y + pl.normal.z * pl.normal.z);
    expect(std::abs(len - 1) <= 1e-12, "plane.normal unit length");
    expect(in01(pl.friction), "plane.friction in [0, 1]");
  }
  const SimulationParams& m = s.simulation;
  expect(std::isfinite(m.frames_per_sec) && m.frames_per_sec > 0, "simulation.frames_per_sec finite and > 0");
  expect(m.simulation_steps >= 1, "simulation.simulation_steps >= 1");
  expect(finite3(m.gravity), "simulation.gravity finite");
  expect(std::isfinite(m.max_stretch) && m.max_stretch >= 0, "simulation.max_stretch finite and >= 0");
  expect(m.constraint_iterations >= 0, "simulation.constraint_iterations >= 0");
  expect(std::isfinite(s.dt()) && s.dt() > 0, "dt() finite and > 0");
}

// scene_to_json's promise: its output loads back to the same Scene, bit for bit.
void check_round_trip(const Scene& a) {
  Scene b;
  try {
    b = parse_scene(scene_to_json(a), "<fuzz>");
  } catch (const SceneError& e) {
    violated(std::string("scene_to_json output does not load back: ") + e.what());
  }
  // Every field, so a new parameter is covered too (the structs' operator== is defaulted).
  expect(a.cloth == b.cloth, "round trip: cloth");
  expect(a.spheres == b.spheres, "round trip: spheres");
  expect(a.planes == b.planes, "round trip: planes");
  expect(a.simulation == b.simulation, "round trip: simulation");
}

}  // namespace

Input split_input(const uint8_t* data, size_t size) {
  Input in;
  const char* p = reinterpret_cast<const char*>(data);
  size_t i = 0;
  while (i < size && p[i] != '\0') ++i;
  in.json.assign(p, i);
  if (i < size) ++i;  // the NUL
  std::string line;
  for (; i <= size; ++i) {
    if (i == size || p[i] == '\n' || p[i] == '\0') {
      if (!line.empty()) in.overrides.push_back(line);
      line.clear();
    } else {
      line += p[i];
    }
  }
  return in;
}

Outcome run_one(const uint8_t* data, size_t size) {
  const Input in = split_input(data, size);
  Outcome out;
  try {
    const Scene s = parse_scene(in.json, "<fuzz>", in.overrides);
    check_valid(s);
    check_round_trip(s);
    out.loaded = true;
  } catch (const SceneError& e) {
    out.error = e.what();
    if (out.error.rfind("<fuzz>", 0) != 0) violated("a SceneError message does not start with the source: " + out.error);
  } catch (const std::exception& e) {
    violated(std::string("an exception other than SceneError escaped parse_scene: ") + typeid(e).name() + ": " +
             e.what());
  } catch (...) {
    violated("a non-std exception escaped parse_scene");
  }
  return out;
}

}  // namespace clothsim::fuzz

#ifdef CLOTHSIM_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  clothsim::fuzz::run_one(data, size);
  return 0;
}
#endif

// libFuzzer target for the scene loader: scene JSON plus `--set` overrides.
//
// Input bytes: the scene JSON text up to the first NUL byte (the whole input if there is
// none); after it, one override ("key.path=value", as given to --set) per line ('\n' or NUL
// separated, empty lines skipped). Each input is passed to
// clothsim::parse_scene(json, "<fuzz>", overrides).
//
// Property: parse_scene either returns a Scene that is fully valid (every value inside the
// range of its row in the parameter table, host/core/scene/scene_table.cpp; unit plane normals and
// rotation axes, pins inside the grid, pinned boxes with min <= max, a grid cloth without mesh
// values, at most kMaxParticles grid particles in all) and that scene_to_json writes out and
// loads back bit for bit, value by value, or throws clothsim::SceneError naming
// the source. Anything else (another exception, a violated property) calls abort(), which
// libFuzzer reports as a crash; ASan/UBSan reports, hangs (-timeout) and OOMs are crashes too.
//
// The same code is built without libFuzzer into clothsim_fuzz_replay (replay_main.cpp,
// --target scene), which ctest runs over tests/fuzz/regressions/ and the seed corpus in every
// build.
#include "fuzz_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "scene/scene_table.hpp"

namespace clothsim::fuzz {
namespace {

[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "fuzz_scene: PROPERTY VIOLATED: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void expect(bool ok, const std::string& what) {
  if (!ok) violated(what);
}

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Key path of a row for messages: "cloth.ks", "sphere[1].radius".
std::string join(const std::string& prefix, const char* key) { return prefix.empty() ? key : prefix + "." + key; }

// Every value inside the range its row of the parameter table states, so a new row is checked
// without an edit here.
class InRange final : public ParamVisitor {
 public:
  explicit InRange(std::string prefix = "") : prefix_(std::move(prefix)) {}
  void number(const ParamInfo& p, double& v) override {
    expect(std::isfinite(v) && v >= p.lo && v <= p.hi, join(prefix_, p.key) + " finite and in its row's range");
  }
  void pair(const ParamInfo& p, std::array<double, 2>& v) override {
    for (double x : v) expect(std::isfinite(x) && x >= p.lo && x <= p.hi, join(prefix_, p.key) + " finite and in its row's range");
  }
  void integer(const ParamInfo& p, int& v) override {
    expect(v >= p.lo && v <= p.hi, join(prefix_, p.key) + " in its row's range");
  }
  void boolean(const ParamInfo&, bool&) override {}
  void vec3(const ParamInfo& p, glm::dvec3& v) override { expect(finite3(v), join(prefix_, p.key) + " finite"); }
  void choice(const ParamInfo& p, int& v) override {
    expect(v >= 0 && size_t(v) < p.choices.size(), join(prefix_, p.key) + " one of its row's choices");
  }
  void text(const ParamInfo& p, std::string& v) override {
    expect(v.find('\0') == std::string::npos, join(prefix_, p.key) + " holds no NUL");
  }
  void indices(const ParamInfo& p, std::vector<int>& v) override {
    for (int i : v) expect(i >= p.lo && i <= p.hi, join(prefix_, p.key) + " each in its row's range");
  }
  void grid_indices(const ParamInfo& p, GridIndices& pins, int nw, int nh) override {
    for (const auto& q : pins)
      expect(q[0] >= 0 && q[1] >= 0 && q[0] < nw && q[1] < nh, join(prefix_, p.key) + " inside the grid");
  }
  void keyframes(const ParamInfo& p, Keyframes& keys) override {
    expect(!keys.empty(), join(prefix_, p.key) + " not empty");
    for (size_t k = 0; k < keys.size(); ++k) {
      expect(std::isfinite(keys[k].time) && keys[k].time >= 0 && finite3(keys[k].value),
             join(prefix_, p.key) + " finite times >= 0 and finite values");
      expect(k == 0 || keys[k].time > keys[k - 1].time, join(prefix_, p.key) + " in ascending time order");
    }
  }
  void object(const ParamInfo& p, ObjectRef& o) override {
    InRange sub(join(prefix_, p.key));
    if (o.present()) o.visit(sub);
  }
  void list(const ParamInfo& p, ListRef& l) override {
    for (size_t i = 0; i < l.size(); ++i) {
      InRange sub(fmt::format("{}[{}]", join(prefix_, p.key), i));
      l.visit(i, sub);
    }
  }

 private:
  std::string prefix_;
};

// Every value of a scene as "key.path" and an exact text (doubles in hex: every bit counts).
class Flatten final : public ParamVisitor {
 public:
  using Values = std::vector<std::pair<std::string, std::string>>;
  Flatten(Values& out, std::string prefix = "") : out_(out), prefix_(std::move(prefix)) {}
  void number(const ParamInfo& p, double& v) override { add(p, fmt::format("{:a}", v)); }
  void pair(const ParamInfo& p, std::array<double, 2>& v) override { add(p, fmt::format("{:a} {:a}", v[0], v[1])); }
  void integer(const ParamInfo& p, int& v) override { add(p, fmt::format("{}", v)); }
  void boolean(const ParamInfo& p, bool& v) override { add(p, v ? "true" : "false"); }
  void vec3(const ParamInfo& p, glm::dvec3& v) override { add(p, fmt::format("{:a} {:a} {:a}", v.x, v.y, v.z)); }
  void choice(const ParamInfo& p, int& v) override { add(p, fmt::format("{}", v)); }
  void text(const ParamInfo& p, std::string& v) override { add(p, v); }
  void indices(const ParamInfo& p, std::vector<int>& v) override {
    std::string s;
    for (int i : v) s += fmt::format("{} ", i);
    add(p, s);
  }
  void grid_indices(const ParamInfo& p, GridIndices& pins, int, int) override {
    std::string s;
    for (const auto& q : pins) s += fmt::format("[{}, {}]", q[0], q[1]);
    add(p, s);
  }
  void keyframes(const ParamInfo& p, Keyframes& keys) override {
    std::string s;
    for (const auto& k : keys) s += fmt::format("[{:a}, {:a} {:a} {:a}]", k.time, k.value.x, k.value.y, k.value.z);
    add(p, s);
  }
  void object(const ParamInfo& p, ObjectRef& o) override {
    add(p, o.present() ? "present" : "absent");
    Flatten sub(out_, join(prefix_, p.key));
    if (o.present()) o.visit(sub);
  }
  void list(const ParamInfo& p, ListRef& l) override {
    add(p, fmt::format("{} elements", l.size()));
    for (size_t i = 0; i < l.size(); ++i) {
      Flatten sub(out_, fmt::format("{}[{}]", join(prefix_, p.key), i));
      l.visit(i, sub);
    }
  }

 private:
  void add(const ParamInfo& p, std::string v) { out_.emplace_back(join(prefix_, p.key), std::move(v)); }
  Values& out_;
  std::string prefix_;
};

Flatten::Values flatten(Scene s) {
  Flatten::Values out;
  Flatten f(out);
  visit_rows(s, f);
  return out;
}

bool unit(const glm::dvec3& v) { return std::abs(std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z) - 1) <= 1e-12; }

void check_valid(Scene s) {
  expect(s.source == "<fuzz>", "Scene::source is the source given");
  InRange rows;
  visit_rows(s, rows);
  // What the rows' ranges cannot say:
  long long n = 0;
  for (const ClothParams* c : s.cloths()) {
    if (c->is_mesh()) {
      expect(c->mesh_path == std::filesystem::path(c->mesh).lexically_normal(), "cloth.mesh_path is cloth.mesh");
      expect(unit(c->rotation_axis), "cloth.rotation_axis unit length");
      if (c->pinned_box)
        expect(c->pinned_box->min.x <= c->pinned_box->max.x && c->pinned_box->min.y <= c->pinned_box->max.y &&
                   c->pinned_box->min.z <= c->pinned_box->max.z,
               "cloth.pinned_box min <= max");
    } else {
      // A grid cloth's mesh rows stay at their defaults (the loader rejects them).
      ClothParams grid;
      expect(c->mesh_path.empty() && c->pinned_vertices.empty() && !c->pinned_box && c->scale == grid.scale &&
                 c->offset == grid.offset && c->rotation_axis == grid.rotation_axis &&
                 c->rotation_degrees == grid.rotation_degrees && c->mass_lumping == grid.mass_lumping,
             "a grid cloth has no mesh values");
      n += (long long)c->num_width_points * c->num_height_points;
    }
  }
  expect(n <= kMaxParticles, "particle count <= kMaxParticles");
  expect((long long)s.particle_count() == n, "particle_count() does not overflow");
  for (const PlaneParams& pl : s.planes) {
    expect(unit(pl.normal), "plane.normal unit length");
  }
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
  // Row by row from the table, naming the first value that differs.
  const Flatten::Values va = flatten(a), vb = flatten(b);
  for (size_t i = 0; i < std::min(va.size(), vb.size()); ++i)
    if (va[i] != vb[i])
      violated(fmt::format("round trip: {} was {}, loads back as {}", va[i].first, va[i].second, vb[i].second));
  expect(va.size() == vb.size(), "round trip: the same number of values");
  // And every member, in case one has no row (the structs' operator== is defaulted).
  expect(a.cloth == b.cloth, "round trip: cloth");
  expect(a.extra_cloths == b.extra_cloths, "round trip: extra_cloths");
  expect(a.spheres == b.spheres, "round trip: spheres");
  expect(a.planes == b.planes, "round trip: planes");
  expect(a.simulation == b.simulation, "round trip: simulation");
  expect(a.wind == b.wind, "round trip: wind");
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

Outcome run_scene(const uint8_t* data, size_t size) {
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
  clothsim::fuzz::run_scene(data, size);
  return 0;
}
#endif

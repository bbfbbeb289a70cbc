// Strict scene loading: every key is known, every value typed, finite and in range,
// and every error names the file and the key path (DESIGN.md §4).
#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene_overrides.hpp"

namespace clothsim {
namespace {

using nlohmann::json;

// A JSON object being read: remembers its key path for messages and which keys were used,
// so anything left over is reported as unknown.
class ObjectReader {
 public:
  ObjectReader(const json& j, std::string source, std::string path)
      : j_(j), source_(std::move(source)), path_(std::move(path)) {
    if (!j_.is_object()) fail(path_, fmt::format("expected an object, got {}", describe(j_)));
  }

  [[noreturn]] void fail(const std::string& key_path, const std::string& what) const {
    if (key_path.empty()) throw SceneError(fmt::format("{}: {}", source_, what));  // the top level
    throw SceneError(fmt::format("{}: {}: {}", source_, key_path, what));
  }
  std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  bool has(const std::string& k) const { return j_.contains(k); }
  const json& raw(const std::string& k) { used_.insert(k); return j_.at(k); }
  const std::string& source() const { return source_; }

  double number(const std::string& k, double lo, double hi, const char* range, bool required,
                double fallback) {
    if (!has(k)) { if (required) missing(k, "a number"); return fallback; }
    return check_number(raw(k), key(k), lo, hi, range);
  }
  int integer(const std::string& k, long long lo, long long hi, bool required, int fallback) {
    if (!has(k)) { if (required) missing(k, "an integer"); return fallback; }
    return check_integer(raw(k), key(k), lo, hi);
  }
  bool boolean(const std::string& k, bool fallback) {
    if (!has(k)) return fallback;
    const json& v = raw(k);
    if (!v.is_boolean()) fail(key(k), fmt::format("expected true or false, got {}", describe(v)));
    return v.get<bool>();
  }
  glm::dvec3 vec3(const std::string& k, bool required, glm::dvec3 fallback) {
    if (!has(k)) { if (required) missing(k, "an array of 3 numbers"); return fallback; }
    const json& v = raw(k);
    if (!v.is_array() || v.size() != 3)
      fail(key(k), fmt::format("expected an array of 3 numbers, got {}", describe(v)));
    glm::dvec3 r;
    for (int c = 0; c < 3; ++c)
      r[c] = check_number(v[c], fmt::format("{}[{}]", key(k), c), -HUGE_VAL, HUGE_VAL, "a finite number");
    return r;
  }
  void reject_unknown() const {
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!used_.count(it.key())) fail(key(it.key()), "unknown key");
  }

  static std::string describe(const json& v) {
    // A --set value that is not JSON becomes a string as typed, possibly not UTF-8: plain
    // dump() would throw json::type_error 316 for it instead of this message naming the key.
    if (v.is_null()) return "null";
    return fmt::format("{} {}", v.type_name(), abbreviate(v.dump(-1, ' ', false, json::error_handler_t::replace), 40));
  }
  double check_number(const json& v, const std::string& kp, double lo, double hi, const char* range) const {
    if (!v.is_number()) fail(kp, fmt::format("expected a number, got {}", describe(v)));
    double d = v.get<double>();
    if (!std::isfinite(d)) fail(kp, fmt::format("expected a finite number, got {}", d));
    if (d < lo || d > hi) fail(kp, fmt::format("expected {}, got {}", range, d));
    return d;
  }
  int check_integer(const json& v, const std::string& kp, long long lo, long long hi) const {
    if (!v.is_number()) fail(kp, fmt::format("expected an integer, got {}", describe(v)));
    double d = v.get<double>();
    if (!std::isfinite(d) || d != std::floor(d)) fail(kp, fmt::format("expected an integer, got {}", describe(v)));
    if (d < double(lo) || d > double(hi)) fail(kp, fmt::format("expected an integer in [{}, {}], got {}", lo, hi, d));
    return int(d);
  }

 private:
  [[noreturn]] void missing(const std::string& k, const char* what) const {
    fail(key(k), fmt::format("missing required key (expected {})", what));
  }
  const json& j_;
  std::string source_, path_;
  std::set<std::string> used_;
};

constexpr double kInf = HUGE_VAL;

ClothParams read_cloth(ObjectReader r) {
  ClothParams c;
  c.width = r.number("width", 1e-9, kInf, "a size > 0 (metres)", true, 0);
  c.height = r.number("height", 1e-9, kInf, "a size > 0 (metres)", true, 0);
  c.num_width_points = r.integer("num_width_points", 2, 1 << 20, true, 0);
  c.num_height_points = r.integer("num_height_points", 2, 1 << 20, true, 0);
  c.thickness = r.number("thickness", 1e-9, kInf, "a thickness > 0 (metres)", true, 0);
  c.orientation = Orientation(r.integer("orientation", 0, 1, true, 0));
  long long n = (long long)c.num_width_points * c.num_height_points;
  if (n > kMaxParticles)
    r.fail(r.key("num_width_points"),
           fmt::format("a {}x{} grid ({} particles) is too large for memory; at most {} particles",
                       c.num_width_points, c.num_height_points, n, kMaxParticles));
  if (r.has("pinned")) {
    const json& p = r.raw("pinned");
    if (!p.is_array()) r.fail(r.key("pinned"), "expected an array of [x, y] grid indices, got " + ObjectReader::describe(p));
    for (size_t k = 0; k < p.size(); ++k) {
      std::string kp = fmt::format("{}[{}]", r.key("pinned"), k);
      if (!p[k].is_array() || p[k].size() != 2)
        r.fail(kp, "expected [x, y] grid indices, got " + ObjectReader::describe(p[k]));
      int x = r.check_integer(p[k][0], kp + "[0]", -(1LL << 31) + 1, (1LL << 31) - 1);
      int y = r.check_integer(p[k][1], kp + "[1]", -(1LL << 31) + 1, (1LL << 31) - 1);
      if (x < 0 || y < 0 || x >= c.num_width_points || y >= c.num_height_points)
        r.fail(kp, fmt::format("index [{}, {}] is outside the {}x{} grid", x, y, c.num_width_points,
                               c.num_height_points));
      c.pinned.push_back({x, y});
    }
  }
  c.enable_structural = r.boolean("enable_structural", c.enable_structural);
  c.enable_shearing = r.boolean("enable_shearing", c.enable_shearing);
  c.enable_bending = r.boolean("enable_bending", c.enable_bending);
  c.damping = r.number("damping", 0, 100, "a percentage in [0, 100]", false, c.damping);
  c.density = r.number("density", 1e-12, kInf, "a density > 0 (kg/m^2)", false, c.density);
  c.ks = r.number("ks", 0, kInf, "a spring constant >= 0 (N/m)", false, c.ks);
  r.reject_unknown();
  return c;
}

double friction(ObjectReader& r) {
  return r.number("friction", 0, 1, "a friction coefficient in [0, 1]", true, 0);
}

SphereParams read_sphere(ObjectReader r) {
  SphereParams s;
  s.origin = r.vec3("origin", true, {});
  s.radius = r.number("radius", 1e-12, kInf, "a radius > 0 (metres)", true, 0);
  s.friction = friction(r);
  r.reject_unknown();
  return s;
}

PlaneParams read_plane(ObjectReader r) {
  PlaneParams p;
  p.point = r.vec3("point", true, {});
  glm::dvec3 n = r.vec3("normal", true, {});
  // Scale by the largest component first: |n| of a finite n such as [1e200, 0, 0] overflows.
  const double m = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
  if (m == 0) r.fail(r.key("normal"), "expected a non-zero normal vector, got [0, 0, 0]");
  // A normal that is already unit to rounding is kept as written, so that normalising is
  // idempotent and scene_to_json's output loads back to the same normal, bit for bit.
  const double len2 = n.x * n.x + n.y * n.y + n.z * n.z;
  if (std::abs(len2 - 1) > 4 * std::numeric_limits<double>::epsilon()) {
    n /= m;
    n /= std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  }
  p.normal = n;
  p.friction = friction(r);
  r.reject_unknown();
  return p;
}

SimulationParams read_simulation(ObjectReader r) {
  SimulationParams s;
  s.frames_per_sec = r.number("frames_per_sec", 1e-6, 1e6, "frames per second in (0, 1e6]", false, s.frames_per_sec);
  s.simulation_steps = r.integer("simulation_steps", 1, 100000, false, s.simulation_steps);
  s.gravity = r.vec3("gravity", false, s.gravity);
  s.max_stretch = r.number("max_stretch", 0, kInf, "a stretch ratio >= 0", false, s.max_stretch);
  s.constraint_iterations = r.integer("constraint_iterations", 0, 10000, false, s.constraint_iterations);
  s.self_collision = r.boolean("self_collision", s.self_collision);
  r.reject_unknown();
  return s;
}

// `sphere` / `plane` may be one object (classic) or an array of objects (extension).
template <class T, class Read>
std::vector<T> read_colliders(ObjectReader& top, const std::string& k, Read read) {
  std::vector<T> out;
  if (!top.has(k)) return out;
  const json& v = top.raw(k);
  if (v.is_array()) {
    for (size_t i = 0; i < v.size(); ++i) out.push_back(read(ObjectReader(v[i], top.source(), fmt::format("{}[{}]", k, i))));
  } else {
    out.push_back(read(ObjectReader(v, top.source(), k)));
  }
  return out;
}

// nlohmann rejects a number too large for a double (1e999, the only way to write a non-finite
// number in JSON) as out_of_range 406, with no position. Re-reading the text with this handler
// finds the key path of that number, so the message names it like every other bad value.
class KeyPathFinder : public nlohmann::json_sax<json> {
 public:
  std::string path, token;  // set when the parse error is reported
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { value(); stack_.push_back({false, "", 0, 0}); return true; }
  bool key(string_t& k) override { stack_.back().key = k; return true; }
  bool end_object() override { stack_.pop_back(); return true; }
  bool start_array(std::size_t) override { value(); stack_.push_back({true, "", 0, 0}); return true; }
  bool end_array() override { stack_.pop_back(); return true; }
  bool parse_error(std::size_t, const std::string& last_token, const nlohmann::detail::exception&) override {
    token = last_token;
    // The failing value has not been counted: in an array its index is `next`.
    for (size_t i = 0; i < stack_.size(); ++i) {
      const Frame& f = stack_[i];
      if (!f.array) path += (path.empty() ? "" : ".") + f.key;
      else path += fmt::format("[{}]", i + 1 == stack_.size() ? f.next : f.cur);
    }
    return false;
  }

 private:
  struct Frame { bool array; std::string key; size_t cur, next; };
  bool value() {
    if (!stack_.empty() && stack_.back().array) stack_.back().cur = stack_.back().next++;
    return true;
  }
  std::vector<Frame> stack_;
};

}  // namespace

std::string Scene::name() const {
  std::filesystem::path p(source);
  return source.empty() || source[0] == '<' ? std::string("default") : p.stem().string();
}

Scene parse_scene(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  json j;
  try {
    j = parse_json_limited(text, source, /*allow_exceptions=*/true);
  } catch (const json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into line:column for people.
    size_t off = std::min<size_t>(e.byte, text.size()), line = 1, col = 1;
    for (size_t i = 0; i + 1 < off; ++i) { if (text[i] == '\n') { ++line; col = 1; } else ++col; }
    throw SceneError(fmt::format("{}:{}:{}: not valid JSON ({})", source, line, col, e.what()));
  } catch (const json::out_of_range&) {  // 406: a number beyond the range of a double
    KeyPathFinder finder;
    json::sax_parse(text, &finder);
    throw SceneError(fmt::format("{}: {}: expected a finite number, got {} (beyond the range of a double)",
                                 source, finder.path.empty() ? "(top level)" : finder.path, finder.token));
  }
  apply_overrides(j, overrides, source);
  ObjectReader top(j, source, "");
  Scene s;
  s.source = source;
  if (!top.has("cloth")) top.fail("cloth", "missing required key (expected the cloth object)");
  s.cloth = read_cloth(ObjectReader(top.raw("cloth"), source, "cloth"));
  s.spheres = read_colliders<SphereParams>(top, "sphere", read_sphere);
  s.planes = read_colliders<PlaneParams>(top, "plane", read_plane);
  if (top.has("simulation")) s.simulation = read_simulation(ObjectReader(top.raw("simulation"), source, "simulation"));
  top.reject_unknown();
  return s;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file, std::ios::binary);
  if (!in || std::filesystem::is_directory(file))
    throw SceneError(fmt::format("{}: cannot open the scene file (does it exist and is it readable?)", file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), file.string(), overrides);
}

Scene default_scene(const std::vector<std::string>& overrides) {
  static const char* kPinned2 = R"({
    "cloth": {"width": 1.0, "height": 1.0, "num_width_points": 50, "num_height_points": 50,
              "thickness": 0.0095, "orientation": 0, "pinned": [[0, 0], [49, 0]]}})";
  return parse_scene(kPinned2, "<built-in pinned2>", overrides);
}

std::string scene_to_json(const Scene& s) {
  auto v3 = [](glm::dvec3 v) { return json::array({v.x, v.y, v.z}); };
  const ClothParams& c = s.cloth;
  json pins = json::array();
  for (auto& p : c.pinned) pins.push_back({p[0], p[1]});
  json j = {{"cloth",
             {{"width", c.width}, {"height", c.height}, {"num_width_points", c.num_width_points},
              {"num_height_points", c.num_height_points}, {"thickness", c.thickness},
              {"orientation", int(c.orientation)}, {"pinned", pins}, {"enable_structural", c.enable_structural},
              {"enable_shearing", c.enable_shearing}, {"enable_bending", c.enable_bending},
              {"damping", c.damping}, {"density", c.density}, {"ks", c.ks}}}};
  j["sphere"] = json::array();
  for (auto& sp : s.spheres) j["sphere"].push_back({{"origin", v3(sp.origin)}, {"radius", sp.radius}, {"friction", sp.friction}});
  j["plane"] = json::array();
  for (auto& pl : s.planes) j["plane"].push_back({{"point", v3(pl.point)}, {"normal", v3(pl.normal)}, {"friction", pl.friction}});
  const SimulationParams& m = s.simulation;
  j["simulation"] = {{"frames_per_sec", m.frames_per_sec}, {"simulation_steps", m.simulation_steps},
                     {"gravity", v3(m.gravity)}, {"max_stretch", m.max_stretch},
                     {"constraint_iterations", m.constraint_iterations}, {"self_collision", m.self_collision}};
  return j.dump(2) + "\n";
}

}  // namespace clothsim

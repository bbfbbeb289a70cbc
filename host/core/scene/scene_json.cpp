// Table-driven scene JSON: the loader and the writer walk the rows of scene_table.cpp, so they
// name no parameter. Every error names the file and the key path (docs/design.md §4).
#include <algorithm>
#include <climits>
#include <cmath>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene/scene_overrides.hpp"
#include "scene/scene_table.hpp"

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

  // The value of key `k`, or nullptr when it is absent (an error when it is required).
  const json* get(const ParamInfo& info, const std::string& expected) {
    if (!of_this_shape(info)) return nullptr;
    if (has(info.key)) return &raw(info.key);
    if (info.required) fail(key(info.key), fmt::format("missing required key (expected {})", expected));
    return nullptr;
  }
  // A row of a grid or of a mesh cloth (param_table.hpp, Shape): false for one of the other
  // kind, which must then be absent.
  bool of_this_shape(const ParamInfo& info) const {
    if (info.shape == Shape::Any) return true;
    const bool mesh = has(kMeshKey);
    if ((info.shape == Shape::Mesh) == mesh) return true;
    if (has(info.key)) {
      if (mesh) fail(key(kMeshKey) + " and " + key(info.key), instead(info));
      fail("", fmt::format("{} is for a mesh cloth ({}); {}", key(info.key), key(kMeshKey), instead(info)));
    }
    return false;
  }
  void reject_unknown() const {
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!used_.count(it.key())) fail(key(it.key()), "unknown key");
  }

  // The row's `instead` with "{}" replaced by this object's key path and a dot.
  std::string instead(const ParamInfo& info) const {
    std::string out = info.instead;
    const std::string prefix = key("");
    for (size_t at = out.find("{}"); at != std::string::npos; at = out.find("{}", at + prefix.size()))
      out.replace(at, 2, prefix);
    return out;
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
  const json& j_;
  std::string source_, path_;
  std::set<std::string> used_;
};

std::string choice_list(const ParamInfo& info) {
  std::string out;
  for (const char* c : info.choices) out += fmt::format("{}\"{}\"", out.empty() ? "" : ", ", c);
  return out;
}

// Reads each row from one object; a key that is absent leaves the member at its default.
class Reader final : public ParamVisitor {
 public:
  explicit Reader(ObjectReader& r) : r_(r) {}

  void number(const ParamInfo& info, double& m) override {
    if (const json* v = r_.get(info, "a number")) m = r_.check_number(*v, r_.key(info.key), info.lo, info.hi, info.expected);
  }
  void pair(const ParamInfo& info, std::array<double, 2>& m) override {  // one number for both, or [warp, weft]
    const json* v = r_.get(info, "a number or [warp, weft]");
    if (!v) return;
    const std::string kp = r_.key(info.key);
    if (!v->is_number() && !(v->is_array() && v->size() == 2))
      r_.fail(kp, fmt::format("expected a number or [warp, weft], got {}", ObjectReader::describe(*v)));
    for (size_t c = 0; c < 2; ++c)
      m[c] = r_.check_number(v->is_array() ? (*v)[c] : *v, v->is_array() ? fmt::format("{}[{}]", kp, c) : kp, info.lo, info.hi, info.expected);
  }
  void integer(const ParamInfo& info, int& m) override {
    // A row without a range takes any int (HUGE_VAL does not convert to an integer).
    const long long lo = (long long)std::max(info.lo, double(INT_MIN)), hi = (long long)std::min(info.hi, double(INT_MAX));
    if (const json* v = r_.get(info, "an integer")) m = r_.check_integer(*v, r_.key(info.key), lo, hi);
  }
  void boolean(const ParamInfo& info, bool& m) override {
    const json* v = r_.get(info, "true or false");
    if (!v) return;
    if (!v->is_boolean()) r_.fail(r_.key(info.key), fmt::format("expected true or false, got {}", ObjectReader::describe(*v)));
    m = v->get<bool>();
  }
  void vec3(const ParamInfo& info, glm::dvec3& m) override {
    const json* v = r_.get(info, "an array of 3 numbers");
    if (!v) return;
    const std::string kp = r_.key(info.key);
    if (!v->is_array() || v->size() != 3)
      r_.fail(kp, fmt::format("expected an array of 3 numbers, got {}", ObjectReader::describe(*v)));
    for (int c = 0; c < 3; ++c)
      m[c] = r_.check_number((*v)[c], fmt::format("{}[{}]", kp, c), -HUGE_VAL, HUGE_VAL, "a finite number");
    if (info.after_read)
      if (const char* bad = info.after_read(m)) r_.fail(kp, bad);
  }
  void choice(const ParamInfo& info, int& m) override {
    const std::string names = choice_list(info);
    const json* v = r_.get(info, "one of " + names);
    if (!v) return;
    for (size_t i = 0; i < info.choices.size() && v->is_string(); ++i)
      if (v->get_ref<const std::string&>() == info.choices[i]) { m = int(i); return; }
    for (const RemovedChoice& r : info.removed_choices)
      if (v->is_string() && v->get_ref<const std::string&>() == r.name)
        r_.fail(r_.key(info.key), fmt::format("\"{}\": {}; expected one of {}", r.name, r.message, names));
    r_.fail(r_.key(info.key), fmt::format("expected one of {}, got {}", names, ObjectReader::describe(*v)));
  }
  void text(const ParamInfo& info, std::string& m) override {
    const std::string expected = *info.expected ? info.expected : "a string";
    const json* v = r_.get(info, expected);
    if (!v) return;
    if (info.index_or_name && v->is_number_unsigned()) {
      m = std::to_string(v->get<uint64_t>());
      return;
    }
    // A --set value that is not JSON is a string as typed: it may not be UTF-8, which
    // scene_to_json could not write. A NUL is no part of a file name.
    bool ok = v->is_string() && !v->get_ref<const std::string&>().empty() &&
              v->get_ref<const std::string&>().find('\0') == std::string::npos;
    if (ok) {
      try {
        (void)v->dump();
      } catch (const json::type_error&) {
        ok = false;
      }
    }
    if (!ok) r_.fail(r_.key(info.key), fmt::format("expected {}, got {}", expected, ObjectReader::describe(*v)));
    m = v->get<std::string>();
  }
  void indices(const ParamInfo& info, std::vector<int>& m) override {
    const json* p = r_.get(info, "an array of integers");
    if (!p) return;
    const std::string kp0 = r_.key(info.key);
    if (!p->is_array()) r_.fail(kp0, "expected an array of integers, got " + ObjectReader::describe(*p));
    const long long lo = (long long)std::max(info.lo, double(INT_MIN)), hi = (long long)std::min(info.hi, double(INT_MAX));
    m.clear();
    for (size_t k = 0; k < p->size(); ++k) {
      const json& e = (*p)[k];
      const std::string kp = fmt::format("{}[{}]", kp0, k);
      // Below the range: the row's own words ("a vertex index >= 0"); else the integer range.
      if (*info.expected && e.is_number() && e.get<double>() < double(lo) &&
          e.get<double>() == std::floor(e.get<double>()))
        r_.fail(kp, fmt::format("expected {}, got {}", info.expected, e.get<double>()));
      m.push_back(r_.check_integer(e, kp, lo, hi));
    }
  }
  // Special case (pinned): the grid must fit in memory before pins are checked against it.
  void grid_indices(const ParamInfo& info, GridIndices& m, int nw, int nh) override {
    if (!r_.of_this_shape(info)) return;  // a mesh cloth: no grid to check
    const long long n = (long long)nw * nh;
    if (n > kMaxParticles)
      r_.fail(r_.key("num_width_points"),
              fmt::format("a {}x{} grid ({} particles) is too large for memory; at most {} particles", nw, nh, n,
                          kMaxParticles));
    const json* p = r_.get(info, "an array of [x, y] grid indices");
    if (!p) return;
    const std::string kp0 = r_.key(info.key);
    if (!p->is_array()) r_.fail(kp0, "expected an array of [x, y] grid indices, got " + ObjectReader::describe(*p));
    m.clear();
    for (size_t k = 0; k < p->size(); ++k) {
      const json& e = (*p)[k];
      std::string kp = fmt::format("{}[{}]", kp0, k);
      if (!e.is_array() || e.size() != 2) r_.fail(kp, "expected [x, y] grid indices, got " + ObjectReader::describe(e));
      int x = r_.check_integer(e[0], kp + "[0]", -(1LL << 31) + 1, (1LL << 31) - 1);
      int y = r_.check_integer(e[1], kp + "[1]", -(1LL << 31) + 1, (1LL << 31) - 1);
      if (x < 0 || y < 0 || x >= nw || y >= nh)
        r_.fail(kp, fmt::format("index [{}, {}] is outside the {}x{} grid", x, y, nw, nh));
      m.push_back({x, y});
    }
  }
  void keyframes(const ParamInfo& info, Keyframes& m) override {
    const char* expected = "a non-empty array of [t, [x, y, z]] keys";
    const json* p = r_.get(info, expected);
    if (!p) return;
    const std::string kp0 = r_.key(info.key);
    if (!p->is_array() || p->empty()) r_.fail(kp0, fmt::format("expected {}, got {}", expected, ObjectReader::describe(*p)));
    m.clear();
    for (size_t k = 0; k < p->size(); ++k) {
      const json& e = (*p)[k];
      const std::string kp = fmt::format("{}[{}]", kp0, k);
      if (!e.is_array() || e.size() != 2 || !e[1].is_array() || e[1].size() != 3)
        r_.fail(kp, "expected a key [t, [x, y, z]], got " + ObjectReader::describe(e));
      Keyframe key;
      key.time = r_.check_number(e[0], kp + "[0]", 0, HUGE_VAL, "a time >= 0 (seconds)");
      if (!m.empty() && !(key.time > m.back().time))
        r_.fail(kp + "[0]", fmt::format("expected keys in ascending time order, got t = {} after t = {}", key.time,
                                        m.back().time));
      for (int c = 0; c < 3; ++c)
        key.value[c] = r_.check_number(e[1][c], fmt::format("{}[1][{}]", kp, c), -HUGE_VAL, HUGE_VAL, "a finite number");
      m.push_back(key);
    }
  }
  void object(const ParamInfo& info, ObjectRef& o) override {
    const json* v = r_.get(info, fmt::format("the {} object", info.key));
    o.set_present(v != nullptr);
    // `string_as`: "cotton" stands for {"preset": "cotton"}; nothing else but an object.
    if (v && info.string_as && !v->is_string() && !v->is_object())
      r_.fail(r_.key(info.key), fmt::format("expected a {} (a string) or an object, got {}", info.string_as, ObjectReader::describe(*v)));
    if (v) read_object(v->is_string() && info.string_as ? json{{info.string_as, *v}} : *v, r_.source(), r_.key(info.key), o);
  }
  // `one_or_many`: one object (the classic cloth, sphere, plane) or an array of them (extension).
  void list(const ParamInfo& info, ListRef& l) override {
    const json* v = r_.get(info, info.one_or_many ? fmt::format("the {} object or an array of them", info.key)
                                                  : std::string("an array of objects"));
    if (!v) return;
    const std::string kp = r_.key(info.key);
    if (!v->is_array() && info.one_or_many) {
      l.resize(1);
      read_element(*v, kp, l, 0);
      return;
    }
    if (!v->is_array()) r_.fail(kp, fmt::format("expected an array of objects, got {}", ObjectReader::describe(*v)));
    if (v->empty() && info.required)
      r_.fail(kp, fmt::format("expected at least one {} object, got an empty array", info.key));
    l.resize(v->size());
    for (size_t i = 0; i < v->size(); ++i) read_element((*v)[i], fmt::format("{}[{}]", kp, i), l, i);
  }

 private:
  void read_element(const json& v, const std::string& path, ListRef& l, size_t i) {
    ObjectReader er(v, r_.source(), path);
    Reader sub(er);
    l.visit(i, sub);
    er.reject_unknown();
  }
  ObjectReader& r_;
};

// Writes each row into one JSON object; finish() then drops what the loader would reject: the
// other kind of cloth's rows (a grid's mesh rows, a mesh's grid rows), the keys a material replaces.
class Writer final : public ParamVisitor {
 public:
  explicit Writer(json& j) : j_(j) {}
  void number(const ParamInfo& info, double& m) override { put(info, m); }
  void pair(const ParamInfo& info, std::array<double, 2>& m) override { put(info, m[0] == m[1] ? json(m[0]) : json::array({m[0], m[1]})); }
  void integer(const ParamInfo& info, int& m) override { put(info, m); }
  void boolean(const ParamInfo& info, bool& m) override { put(info, m); }
  void vec3(const ParamInfo& info, glm::dvec3& m) override { put(info, json::array({m.x, m.y, m.z})); }
  void choice(const ParamInfo& info, int& m) override { put(info, info.choices[size_t(m)]); }
  void text(const ParamInfo& info, std::string& m) override {
    if (std::string_view(info.key) == kMeshKey) mesh_ = !m.empty();
    if (!m.empty()) put(info, m);  // absent, not "": the loader takes no empty string
  }
  void indices(const ParamInfo& info, std::vector<int>& m) override { put(info, m); }
  void grid_indices(const ParamInfo& info, GridIndices& m, int, int) override {
    json pins = json::array();
    for (auto& p : m) pins.push_back({p[0], p[1]});
    put(info, std::move(pins));
  }
  void keyframes(const ParamInfo& info, Keyframes& m) override {
    json keys = json::array();
    for (auto& k : m) keys.push_back({k.time, json::array({k.value.x, k.value.y, k.value.z})});
    put(info, std::move(keys));
  }
  void object(const ParamInfo& info, ObjectRef& o) override {
    if (o.present()) put(info, write_object(o));
  }
  // A `single_as_object` list of one is written as that object (a classic one-cloth scene).
  void list(const ParamInfo& info, ListRef& l) override {
    json a = json::array();
    for (size_t i = 0; i < l.size(); ++i) {
      json e = json::object();
      Writer w(e);
      l.visit(i, w);
      w.finish();
      a.push_back(std::move(e));
    }
    if (info.single_as_object && a.size() == 1) put(info, std::move(a[0]));
    else put(info, std::move(a));
  }
  void finish() {
    for (const ParamInfo* info : shaped_)
      if ((info->shape == Shape::Mesh) != mesh_) j_.erase(info->key);
    if (j_.contains("material")) for (std::string_view k : kKeysMaterialReplaces) j_.erase(std::string(k));
  }

 private:
  void put(const ParamInfo& info, json v) {
    if (info.shape != Shape::Any) shaped_.push_back(&info);
    j_[info.key] = std::move(v);
  }
  json& j_;
  bool mesh_ = false;
  std::vector<const ParamInfo*> shaped_;
};

}  // namespace

void read_object(const json& j, const std::string& source, const std::string& path, ObjectRef& object) {
  ObjectReader r(j, source, path);
  Reader reader(r);
  object.visit(reader);
  r.reject_unknown();
}

json write_object(ObjectRef& object) {
  json j = json::object();
  Writer w(j);
  object.visit(w);
  w.finish();
  return j;
}

}  // namespace clothsim

// Table-driven scene JSON: the loader and the writer walk the rows of scene_table.cpp, so they
// name no parameter. Every error names the file and the key path (DESIGN.md §4).
#include <algorithm>
#include <climits>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene_overrides.hpp"
#include "scene_table.hpp"

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
    if (has(info.key)) return &raw(info.key);
    if (info.required) fail(key(info.key), fmt::format("missing required key (expected {})", expected));
    return nullptr;
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
    r_.fail(r_.key(info.key), fmt::format("expected one of {}, got {}", names, ObjectReader::describe(*v)));
  }
  // Special case (pinned): the grid must fit in memory before pins are checked against it.
  void grid_indices(const ParamInfo& info, GridIndices& m, int nw, int nh) override {
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
    if (v) read_object(*v, r_.source(), r_.key(info.key), o);
  }
  // `one_or_many`: one object (the classic sphere/plane) or an array of them (extension).
  void list(const ParamInfo& info, ListRef& l) override {
    const json* v = r_.get(info, "an array of objects");
    if (!v) return;
    const std::string kp = r_.key(info.key);
    if (!v->is_array() && info.one_or_many) {
      l.resize(1);
      read_element(*v, kp, l, 0);
      return;
    }
    if (!v->is_array()) r_.fail(kp, fmt::format("expected an array of objects, got {}", ObjectReader::describe(*v)));
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

// Writes each row into one JSON object.
class Writer final : public ParamVisitor {
 public:
  explicit Writer(json& j) : j_(j) {}
  void number(const ParamInfo& info, double& m) override { j_[info.key] = m; }
  void integer(const ParamInfo& info, int& m) override { j_[info.key] = m; }
  void boolean(const ParamInfo& info, bool& m) override { j_[info.key] = m; }
  void vec3(const ParamInfo& info, glm::dvec3& m) override { j_[info.key] = json::array({m.x, m.y, m.z}); }
  void choice(const ParamInfo& info, int& m) override { j_[info.key] = info.choices[size_t(m)]; }
  void grid_indices(const ParamInfo& info, GridIndices& m, int, int) override {
    json pins = json::array();
    for (auto& p : m) pins.push_back({p[0], p[1]});
    j_[info.key] = std::move(pins);
  }
  void keyframes(const ParamInfo& info, Keyframes& m) override {
    json keys = json::array();
    for (auto& k : m) keys.push_back({k.time, json::array({k.value.x, k.value.y, k.value.z})});
    j_[info.key] = std::move(keys);
  }
  void object(const ParamInfo& info, ObjectRef& o) override {
    if (o.present()) j_[info.key] = write_object(o);
  }
  void list(const ParamInfo& info, ListRef& l) override {
    json a = json::array();
    for (size_t i = 0; i < l.size(); ++i) {
      json e = json::object();
      Writer w(e);
      l.visit(i, w);
      a.push_back(std::move(e));
    }
    j_[info.key] = std::move(a);
  }

 private:
  json& j_;
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
  return j;
}

}  // namespace clothsim

#include "scene/scene_overrides.hpp"

#include <cctype>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene/scene.hpp"
#include "scene/scene_table.hpp"

namespace clothsim {
namespace {

struct Segment {
  std::string key;  // empty for an array index
  long index = -1;
};

std::vector<Segment> split_path(const std::string& path, const std::string& where) {
  std::vector<Segment> out;
  size_t i = 0;
  auto bad = [&](const char* why) -> std::vector<Segment> {
    throw SceneError(fmt::format("{}: {}", where, why));
  };
  while (i < path.size()) {
    if (path[i] == '[') {
      size_t close = path.find(']', i);
      if (close == std::string::npos || close == i + 1) return bad("unclosed or empty [index] in the key path");
      std::string num = path.substr(i + 1, close - i - 1);
      for (char c : num) if (!std::isdigit((unsigned char)c)) return bad("an [index] must be a non-negative integer");
      if (num.size() > 6) return bad("an [index] is out of range");
      out.push_back({"", std::stol(num)});
      i = close + 1;
      if (i < path.size() && path[i] == '.') ++i;
    } else {
      size_t end = path.find_first_of(".[", i);
      if (end == std::string::npos) end = path.size();
      if (end == i) return bad("empty key in the key path");
      out.push_back({path.substr(i, end - i), -1});
      i = end;
      if (i < path.size() && path[i] == '.') ++i;
    }
    if (i == path.size() && path.back() == '.') return bad("empty key in the key path");
  }
  if (out.empty()) return bad("empty key path");
  return out;
}

// The top-level row of `key` when it is a list usually written as one object (the cloth), else
// nullptr.
const ParamInfo* single_object_list(const std::string& key) {
  for (const Param<Scene>& p : param_rows<Scene>())
    if (p.info.single_as_object && key == p.info.key) return &p.info;
  return nullptr;
}

// A cloth switched to a mesh by --set: its grid keys go, which the loader would otherwise
// report as "cloth.mesh and cloth.width: ..." (the grid rows and kMeshKey exclude each other).
void drop_grid_keys(nlohmann::json& cloth) {
  for (const Param<ClothParams>& p : param_rows<ClothParams>())
    if (p.info.shape == Shape::Grid) cloth.erase(p.info.key);
}

}  // namespace

nlohmann::json parse_json_limited(const std::string& text, const std::string& where, bool allow_exceptions) {
  auto limit = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxJsonDepth)
      throw SceneError(fmt::format("{}: arrays and objects nested deeper than {} levels", where, kMaxJsonDepth));
    return true;
  };
  return nlohmann::json::parse(text, limit, allow_exceptions);
}

std::string abbreviate(const std::string& text, size_t max) {
  if (text.size() <= max) return text;
  size_t n = max < 3 ? 0 : max - 3;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // a continuation byte
  return text.substr(0, n) + "...";
}

void apply_overrides(nlohmann::json& scene, const std::vector<std::string>& overrides, const std::string& source) {
  for (const std::string& o : overrides) {
    // A fuzzed --set can be megabytes long: the message shows its start.
    std::string where = fmt::format("{}: --set {}", source, abbreviate(o, 80));
    size_t eq = o.find('=');
    if (eq == std::string::npos || eq == 0)
      throw SceneError(fmt::format("{}: expected key.path=value (e.g. --set cloth.ks=500)", where));
    std::vector<Segment> path = split_path(o.substr(0, eq), where);
    if (path.size() > size_t(kMaxJsonDepth))
      throw SceneError(fmt::format("{}: a key path of more than {} parts", where, kMaxJsonDepth));
    std::string text = o.substr(eq + 1);
    nlohmann::json value = parse_json_limited(text, where, /*allow_exceptions=*/false);
    if (value.is_discarded()) value = text;

    nlohmann::json* node = &scene;
    nlohmann::json* cloth = nullptr;  // the cloth object the path has reached, if any
    for (size_t k = 0; k < path.size(); ++k) {
      const Segment& s = path[k];
      // `cloth` (a single_object_list) may be one object or an array: `cloth.ks` is the first
      // cloth's in both, `cloth[0].ks` too, `cloth[1].ks` the second's in an array.
      const bool one_or_many = k == 1 && single_object_list(path[0].key);
      if (s.index >= 0) {
        if (one_or_many && node->is_object() && s.index == 0) {
          cloth = node;
          continue;
        }
        if (!node->is_array() || size_t(s.index) >= node->size())
          throw SceneError(fmt::format("{}: [{}] does not name an existing array element", where, s.index));
        node = &(*node)[size_t(s.index)];
        if (one_or_many) cloth = node;
      } else {
        if (one_or_many && node->is_array() && !node->empty()) node = &(*node)[0];
        if (one_or_many) cloth = node;
        if (node->is_null()) *node = nlohmann::json::object();
        if (!node->is_object())
          throw SceneError(fmt::format("{}: '{}' is inside a value that is not an object", where, s.key));
        node = &(*node)[s.key];
      }
    }
    *node = std::move(value);
    // `--set cloth.mesh=x.obj` turns a grid cloth into a mesh cloth.
    if (cloth && cloth->is_object() && path[0].key == "cloth" && path.back().key == kMeshKey)
      if (auto it = cloth->find(kMeshKey); it != cloth->end() && &*it == node) drop_grid_keys(*cloth);
  }
}

}  // namespace clothsim

// Scene files: the JSON text and --set overrides around the table-driven reader and writer
// (scene_json.cpp, over the rows of scene_table.cpp). Errors name the file and the key path.
#include "scene/scene.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/input_file.hpp"
#include "scene/materials.hpp"
#include "scene/scene_overrides.hpp"
#include "scene/scene_table.hpp"

namespace clothsim {
namespace {

using nlohmann::json;

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

// What the rows cannot say about a cloth, and where its mesh file is. `key` is its key path
// ("cloth", or "cloth[1]" in an array).
// A box's min <= max in each axis; `key` names the box ("cloth.pinned_box").
void check_box(const std::optional<BoxParams>& box, const std::string& source, const std::string& key) {
  if (!box) return;
  const glm::dvec3 lo = box->min, hi = box->max;
  if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z)
    throw SceneError(fmt::format("{}: {}: expected min <= max in each of x, y, z, got min [{}, {}, {}] and max "
                                 "[{}, {}, {}]",
                                 source, key, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z));
}

// Each attachment of cloth `c` (its key path `key`) names a collider of the scene, picks some
// vertices.
void check_attachments(const Scene& s, const ClothParams& c, const std::string& source, const std::string& key) {
  for (size_t k = 0; k < c.attachments.size(); ++k) {
    const AttachmentParams& a = c.attachments[k];
    const std::string at = fmt::format("{}.attachments[{}]", key, k);
    if (!find_collider(s, a.collider))
      throw SceneError(fmt::format("{}: {}.collider: expected a collider of the scene (\"sphere\", \"sphere[1]\", "
                                   "\"plane[0]\", \"mesh[0]\", ...; it has {} sphere(s), {} plane(s), {} mesh(es)), "
                                   "got \"{}\"",
                                   source, at, s.spheres.size(), s.planes.size(), s.meshes.size(), printable(a.collider)));
    check_box(a.box, source, at + ".box");
    if (a.vertices.empty() && !a.box)
      throw SceneError(fmt::format("{}: {}: expected `vertices` or `box` (which vertices follow {})", source, at,
                                   printable(a.collider)));
  }
}

// Each seam of cloth `c` (cloth index `index` of `cloths`) says one way of picking each side's
// vertices, names a cloth that exists, and an edge only of a grid; the lists' lengths and
// indices are checked when the cloths are built (a mesh's vertex count is known then).
void check_seams(const Scene& s, const ClothParams& c, size_t cloths, const std::string& source,
                 const std::string& key) {
  static const char* const kEdges[] = {"x_min", "x_max", "y_min", "y_max"};
  for (size_t k = 0; k < c.seams.size(); ++k) {
    const SeamParams& seam = c.seams[k];
    const std::string at = fmt::format("{}.seams[{}]", key, k);
    if (seam.to_cloth >= int(cloths))
      throw SceneError(fmt::format("{}: {}.to_cloth: expected the index of one of the scene's {} cloth(s) (0 to {}), "
                                   "got {}",
                                   source, at, cloths, cloths - 1, seam.to_cloth));
    const ClothParams& other = seam.to_cloth < 0 ? c : *s.cloths()[size_t(seam.to_cloth)];
    auto side = [&](const std::vector<int>& vertices, const std::string& edge, const std::optional<BoxParams>& box,
                    const ClothParams& cloth, const char* prefix) {
      const int ways = int(!vertices.empty()) + int(!edge.empty()) + int(box.has_value());
      if (ways != 1)
        throw SceneError(fmt::format("{}: {}: expected exactly one of `{}vertices`, `{}edge` and `{}box`, got {}",
                                     source, at, prefix, prefix, prefix, ways));
      check_box(box, source, fmt::format("{}.{}box", at, prefix));
      if (edge.empty()) return;
      if (std::find(std::begin(kEdges), std::end(kEdges), edge) == std::end(kEdges))
        throw SceneError(fmt::format("{}: {}.{}edge: expected \"x_min\", \"x_max\", \"y_min\" or \"y_max\", got \"{}\"",
                                     source, at, prefix, printable(edge)));
      if (cloth.is_mesh())
        throw SceneError(fmt::format("{}: {}.{}edge: a mesh cloth has no grid edges: expected `{}vertices` or `{}box`",
                                     source, at, prefix, prefix, prefix));
    };
    side(seam.vertices, seam.edge, seam.box, c, "");
    side(seam.to_vertices, seam.to_edge, seam.to_box, other, "to_");
  }
}

void finish_cloth(ClothParams& c, const std::string& source, const std::string& key) {
  check_box(c.pinned_box, source, key + ".pinned_box");
  // Relative to the scene file's directory; a scene that is no file ("<built-in>", "<fuzz>"):
  // to the current directory.
  c.mesh_path.clear();
  if (c.is_mesh()) {
    const std::filesystem::path mesh(c.mesh);
    const bool file = !source.empty() && source[0] != '<';
    c.mesh_path = (file ? std::filesystem::path(source).parent_path() / mesh : mesh).lexically_normal();
  }
}

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
  Scene s;
  s.source = source;
  read_params(j, source, "", s);  // the rows of scene_table.cpp
  // Special cases, across rows: see finish_cloth; and the grid cloths together must fit in
  // memory like one (a mesh is counted once it is loaded).
  const bool array = j.is_object() && j.contains("cloth") && j["cloth"].is_array();
  long long particles = 0;
  for (size_t i = 0; i <= s.extra_cloths.size(); ++i) {
    ClothParams& c = i == 0 ? s.cloth : s.extra_cloths[i - 1];
    const std::string key = array ? fmt::format("cloth[{}]", i) : std::string("cloth");
    finish_cloth(c, source, key);
    if (c.material) {
      resolve_material(*c.material, source, key + ".material");
      if (s.simulation.solver != Solver::Fabric)
        throw SceneError(fmt::format("{}: {}.material: a material in physical units needs the fabric solver: set "
                                     "simulation.solver to \"fabric\" (the classic solver takes density and ks)",
                                     source, key));
      // The material replaces these: given both, which one holds would be a guess.
      const json& cj = array ? j["cloth"][i] : j["cloth"];
      for (std::string_view k : kKeysMaterialReplaces)
        if (cj.is_object() && cj.contains(k))
          throw SceneError(fmt::format("{}: {}.{}: a cloth with a material takes its mass and stiffness from {}.material; "
                                       "remove one of the two", source, key, k, key));
    }
    check_attachments(s, c, source, key);
    check_seams(s, c, s.extra_cloths.size() + 1, source, key);
    if (c.is_mesh()) continue;
    particles += (long long)c.num_width_points * c.num_height_points;
    if (particles > kMaxParticles)
      throw SceneError(fmt::format("{}: {}.num_width_points: the grid cloths have {} particles in all, too many for "
                                   "memory; at most {} particles",
                                   source, key, particles, kMaxParticles));
  }
  // A mesh collider's file, relative to the scene file like a mesh cloth's.
  const bool file = !source.empty() && source[0] != '<';
  auto resolve = [&](const std::string& f) {
    return (file ? std::filesystem::path(source).parent_path() / f : std::filesystem::path(f)).lexically_normal();
  };
  for (size_t k = 0; k < s.meshes.size(); ++k) {
    MeshColliderParams& m = s.meshes[k];
    m.file_path = resolve(m.file);
    if (!m.point_cache.empty()) m.point_cache_path = resolve(m.point_cache);
    if (!m.sequence.empty()) m.sequence_path = resolve(m.sequence);
    // One source of motion for the vertices: bones, a point cache or an OBJ sequence.
    const int sources = !m.animation.empty() + !m.point_cache.empty() + !m.sequence.empty();
    if (sources > 1)
      throw SceneError(fmt::format("{}: {}: expected at most one of animation, point_cache and sequence (what moves "
                                   "the vertices), got {}",
                                   source, s.meshes.size() == 1 ? std::string("mesh") : fmt::format("mesh[{}]", k),
                                   sources));
  }
  return s;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  // Checked and read by read_input_file: a FIFO or /dev/zero given as the scene is refused
  // before any read, never read forever. 256 MiB holds the pins of the largest cloth.
  std::string text;
  try {
    text = read_input_file(file, uint64_t(256) << 20);
  } catch (const std::runtime_error& e) {
    throw SceneError(fmt::format("{}: cannot read the scene file: {}", file.empty() ? "\"\"" : printable(file.string()),
                                 e.what()));
  }
  return parse_scene(text, file.string(), overrides);
}

Scene default_scene(const std::vector<std::string>& overrides) {
  static const char* kPinned2 = R"({
    "cloth": {"width": 1.0, "height": 1.0, "num_width_points": 50, "num_height_points": 50,
              "thickness": 0.0095, "orientation": 0, "pinned": [[0, 0], [49, 0]]}})";
  return parse_scene(kPinned2, "<built-in pinned2>", overrides);
}

std::optional<ColliderRef> find_collider(const Scene& scene, const std::string& key) {
  const struct {
    const char* name;
    int kind;
    size_t count;
  } kinds[] = {{"sphere", 1, scene.spheres.size()}, {"plane", 2, scene.planes.size()}, {"mesh", 3, scene.meshes.size()}};
  for (const auto& k : kinds) {
    const std::string name = k.name;
    if (key.rfind(name, 0) != 0) continue;
    const std::string rest = key.substr(name.size());
    size_t index = 0;
    if (!rest.empty()) {
      if (rest.size() < 3 || rest.front() != '[' || rest.back() != ']' || rest.size() > 12) return std::nullopt;
      for (size_t c = 1; c + 1 < rest.size(); ++c) {
        if (rest[c] < '0' || rest[c] > '9') return std::nullopt;
        index = index * 10 + size_t(rest[c] - '0');
      }
    }
    if (index >= k.count) return std::nullopt;
    return ColliderRef{k.kind, index};
  }
  return std::nullopt;
}

std::string scene_to_json(const Scene& s) { return write_params(s).dump(2) + "\n"; }

}  // namespace clothsim

namespace clothsim {

std::vector<const ClothParams*> Scene::cloths() const {
  std::vector<const ClothParams*> all{&cloth};
  for (auto& c : extra_cloths) all.push_back(&c);
  return all;
}

int Scene::particle_count() const {
  long long n = 0;
  for (const ClothParams* c : cloths())
    if (!c->is_mesh()) n += (long long)c->num_width_points * c->num_height_points;
  return int(n);
}

}  // namespace clothsim

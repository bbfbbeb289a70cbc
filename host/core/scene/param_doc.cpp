// docs/parameters.md, written from the parameter table (scene_table.cpp) so that the reference
// cannot drift from what the loader accepts: a ctest test compares the committed file.
#include "scene/param_doc.hpp"

#include <string_view>

#include <fmt/format.h>

#include "scene/scene_table.hpp"

namespace clothsim {
namespace {

std::string num(double v) {
  if (v == HUGE_VAL) return "∞";
  if (v == -HUGE_VAL) return "-∞";
  return fmt::format("{}", v);
}

std::string range(const ParamInfo& p) {
  const bool lo = p.lo != -HUGE_VAL, hi = p.hi != HUGE_VAL;
  if (lo && hi) return fmt::format("[{}, {}]", num(p.lo), num(p.hi));
  if (lo) return "≥ " + num(p.lo);
  if (hi) return "≤ " + num(p.hi);
  return "finite";
}

std::string viewer(const Widget& w, const ParamInfo& p) {
  switch (w.style) {
    case Widget::Hidden: return "";
    case Widget::Checkbox: return "checkbox";
    case Widget::ReadOnly: return "read-only (edit the file, Reload)";
    case Widget::Drag: break;
  }
  std::string s = "drag";
  if (w.lo != w.hi) s += fmt::format(" [{}, {}]", num(w.lo), num(w.hi));
  if (w.scale != 1) s += fmt::format(" in {} (= {} × {})", w.unit ? w.unit : p.unit, p.key, num(w.scale));
  return s;
}

// Collects the table rows of one section (a top-level object); nested objects and lists add
// their own row and then their element's rows, with the key path relative to the section.
class Doc final : public ParamVisitor {
 public:
  Doc(std::string& out, std::string prefix) : out_(out), prefix_(std::move(prefix)) {}

  void number(const ParamInfo& p, double& v) override { add(p, "number", p.required ? "" : num(v), range(p)); }
  void pair(const ParamInfo& p, std::array<double, 2>& v) override {
    add(p, "number or [warp, weft]", p.required ? "" : fmt::format("[{}, {}]", num(v[0]), num(v[1])), range(p));
  }
  void integer(const ParamInfo& p, int& v) override {
    add(p, "integer", p.required ? "" : fmt::format("{}", v), range(p));
  }
  void boolean(const ParamInfo& p, bool& v) override { add(p, "boolean", v ? "true" : "false", ""); }
  void vec3(const ParamInfo& p, glm::dvec3& v) override {
    add(p, "[x, y, z]", p.required ? "" : fmt::format("[{}, {}, {}]", num(v.x), num(v.y), num(v.z)), "finite");
  }
  void choice(const ParamInfo& p, int& v) override {
    std::string names;
    for (const char* c : p.choices) names += fmt::format("{}`\"{}\"`", names.empty() ? "" : " \\| ", c);
    add(p, "string", fmt::format("`\"{}\"`", p.choices[size_t(v)]), names);
  }
  void text(const ParamInfo& p, std::string& v) override {
    add(p, "string", v.empty() ? "absent" : fmt::format("`\"{}\"`", v), "non-empty");
  }
  void indices(const ParamInfo& p, std::vector<int>&) override { add(p, "[i, ...]", "[]", "each " + range(p)); }
  void grid_indices(const ParamInfo& p, GridIndices&, int, int) override {
    add(p, "[[x, y], ...]", "[]", "inside the grid");
  }
  void keyframes(const ParamInfo& p, Keyframes&) override {
    add(p, "[[t, [x, y, z]], ...]", "", "t ≥ 0 ascending, finite");
  }
  void object(const ParamInfo& p, ObjectRef& o) override {
    add(p, "object", o.optional() ? "absent" : "", "");
    Doc sub(out_, prefix_ + p.key + ".");
    o.visit(sub);
  }
  void list(const ParamInfo& p, ListRef& l) override {
    add(p, p.one_or_many ? "object or array of objects" : "array of objects", "[]", "");
    Doc sub(out_, prefix_ + p.key + "[i].");
    l.visit_default(sub);
  }

 private:
  void add(const ParamInfo& p, const char* type, const std::string& def, const std::string& valid) {
    // A row of one kind of cloth says so: required only there, absent in the other.
    const char* shape = p.shape == Shape::Grid ? "grid" : p.shape == Shape::Mesh ? "mesh" : nullptr;
    const std::string presence =
        p.required ? (shape ? fmt::format("**required** ({} cloth)", shape) : std::string("**required**")) : def;
    const std::string meaning = shape ? fmt::format("{} cloth only: {}", shape, p.meaning) : std::string(p.meaning);
    out_ += fmt::format("| `{}{}` | {} | {} | {} | {} | {} | {} |\n", prefix_, p.key, type, presence, valid, p.unit,
                        meaning, viewer(p.widget, p));
  }
  std::string& out_;
  std::string prefix_;
};

// The top level: one section per object or list, with its rows.
class Sections final : public ParamVisitor {
 public:
  explicit Sections(std::string& out) : out_(out) {}
  void object(const ParamInfo& p, ObjectRef& o) override {
    head(p, p.required ? "required" : "optional");
    Doc rows(out_, "");
    o.visit(rows);
  }
  void list(const ParamInfo& p, ListRef& l) override {
    head(p, p.required ? "required; the rows below apply to each element"
                       : "optional; the rows below apply to each element");
    Doc rows(out_, "");
    l.visit_default(rows);
  }
  // Scalars at the top level would be a new kind of scene file; none exist.
  void number(const ParamInfo&, double&) override {}
  void pair(const ParamInfo&, std::array<double, 2>&) override {}
  void integer(const ParamInfo&, int&) override {}
  void boolean(const ParamInfo&, bool&) override {}
  void vec3(const ParamInfo&, glm::dvec3&) override {}
  void choice(const ParamInfo&, int&) override {}
  void text(const ParamInfo&, std::string&) override {}
  void indices(const ParamInfo&, std::vector<int>&) override {}
  void grid_indices(const ParamInfo&, GridIndices&, int, int) override {}
  void keyframes(const ParamInfo&, Keyframes&) override {}

 private:
  void head(const ParamInfo& p, const char* presence) {
    out_ += fmt::format("\n## `{}`\n\n{} ({}).\n\n", p.key, p.meaning, presence);
    out_ += "| key | type | default | valid | unit | meaning | viewer |\n|---|---|---|---|---|---|---|\n";
  }
  std::string& out_;
};

}  // namespace

std::string parameters_markdown() {
  std::string out =
      "# Scene parameters\n\n"
      "<!-- Generated from host/core/scene/scene_table.cpp by clothsim-params-doc; do not edit.\n"
      "     Regenerate: cmake --build build --target parameters-doc -->\n\n"
      "Every key a scene file may hold (README: Scene files), with its default when left out. Loading\n"
      "is strict: an unknown key, a wrong type, a non-finite or out-of-range value is an error naming\n"
      "the file and the key path (exit 2). `--set key.path=value` overrides any of them, e.g.\n"
      "`--set cloth.ks=500`, `--set sphere[0].radius=0.3`. The viewer column says how the\n"
      "*Simulation* panel shows the key (its label is the key).\n";
  // Which cloth keys go together, from the rows.
  std::string grid, mesh;
  for (const Param<ClothParams>& p : param_rows<ClothParams>()) {
    std::string& to = p.info.shape == Shape::Grid ? grid : mesh;
    if (p.info.shape != Shape::Any && p.info.key != std::string_view(kMeshKey))
      to += fmt::format("{}`{}`", to.empty() ? "" : ", ", p.info.key);
  }
  out += fmt::format(
      "\n`cloth` is one cloth object, or an array of them: several cloths in one scene, each with its own\n"
      "keys, sharing the simulation; errors name `cloth[1].ks` and so on. `--set cloth.ks=...` edits the\n"
      "first cloth, `--set cloth[1].ks=...` the second.\n\n"
      "A cloth is a grid or a mesh. A grid cloth has the grid keys\n{};\n"
      "a mesh cloth has `{}`, the mesh file's path relative to the scene file, and may have\n{}.\n"
      "The keys of one kind are an error in a cloth of the other, and the grid keys marked required\n"
      "are required of a grid cloth only. `--set cloth.{}=file.obj` drops that cloth's grid keys.\n",
      grid, kMeshKey, mesh, kMeshKey);
  Scene defaults;
  Sections top(out);
  visit_rows(defaults, top);
  return out;
}

}  // namespace clothsim

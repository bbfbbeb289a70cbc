// The viewer's Dear ImGui panels. Labels are the scene JSON key names (one name end to end);
// the Simulation panel is made from the parameter table (host/core/scene/scene_table.cpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <imgui.h>

#include "io/output_file.hpp"
#include "scene/scene_table.hpp"
#include "viewer_state.hpp"

namespace clothsim {
namespace {

// Whether the rows visited hold a non-empty kMeshKey (a mesh cloth): the panel then skips the
// grid rows, else the mesh rows (param_table.hpp, Shape).
class MeshProbe final : public ParamVisitor {
 public:
  bool mesh = false;
  void text(const ParamInfo& p, std::string& v) override {
    if (std::string_view(p.key) == kMeshKey) mesh = !v.empty();
  }
  void number(const ParamInfo&, double&) override {}
  void pair(const ParamInfo&, std::array<double, 2>&) override {}
  void integer(const ParamInfo&, int&) override {}
  void boolean(const ParamInfo&, bool&) override {}
  void vec3(const ParamInfo&, glm::dvec3&) override {}
  void choice(const ParamInfo&, int&) override {}
  void indices(const ParamInfo&, std::vector<int>&) override {}
  void grid_indices(const ParamInfo&, GridIndices&, int, int) override {}
  void keyframes(const ParamInfo&, Keyframes&) override {}
  void object(const ParamInfo&, ObjectRef&) override {}
  void list(const ParamInfo&, ListRef&) override {}
};

// The Simulation panel's widgets, one per row of the parameter table that has a widget:
// the labels are the JSON keys, values are shown in the row's display unit.
class PanelRows final : public ParamVisitor {
 public:
  bool changed = false;
  std::vector<std::string> fixed;  // the read-only rows, listed together under the widgets

  void number(const ParamInfo& p, double& v) override {
    if (!shown(p)) return;
    const Widget& w = p.widget;
    if (w.style == Widget::ReadOnly) fixed.push_back(fmt::format("{} = {}", label(p), v));
    if (w.style != Widget::Drag) return;
    float f = float(v * w.scale);
    if (ImGui::DragFloat(label(p).c_str(), &f, w.speed, float(w.lo), float(w.hi), w.format)) {
      v = (w.lo < w.hi ? std::clamp(double(f), w.lo, w.hi) : double(f)) / w.scale;
      changed = true;
    }
  }
  // [warp, weft]: one drag each, in the row's unit.
  void pair(const ParamInfo& p, std::array<double, 2>& v) override {
    if (!shown(p)) return;
    if (p.widget.style == Widget::ReadOnly) fixed.push_back(fmt::format("{} = [{}, {}]", label(p), v[0], v[1]));
    if (p.widget.style != Widget::Drag) return;
    float f[2] = {float(v[0]), float(v[1])};
    if (ImGui::DragFloat2(label(p).c_str(), f, p.widget.speed, float(p.widget.lo), float(p.widget.hi), p.widget.format)) {
      for (int k = 0; k < 2; ++k) v[size_t(k)] = p.widget.lo < p.widget.hi ? std::clamp(double(f[k]), p.widget.lo, p.widget.hi) : double(f[k]);
      changed = true;
    }
  }
  void integer(const ParamInfo& p, int& v) override {
    if (!shown(p)) return;
    const Widget& w = p.widget;
    if (w.style == Widget::ReadOnly) fixed.push_back(fmt::format("{} = {}", label(p), v));
    if (w.style != Widget::Drag) return;
    if (ImGui::DragInt(label(p).c_str(), &v, w.speed, int(w.lo), int(w.hi), w.format)) {
      if (w.lo < w.hi) v = std::clamp(v, int(w.lo), int(w.hi));  // a typed value may be outside
      changed = true;
    }
  }
  void boolean(const ParamInfo& p, bool& v) override {
    if (shown(p) && p.widget.style == Widget::Checkbox) changed |= ImGui::Checkbox(p.key, &v);
  }
  void vec3(const ParamInfo& p, glm::dvec3& v) override {
    if (!shown(p)) return;
    if (p.widget.style == Widget::ReadOnly) fixed.push_back(fmt::format("{} = [{}, {}, {}]", label(p), v.x, v.y, v.z));
    if (p.widget.style != Widget::Drag) return;
    float f[3] = {float(v.x), float(v.y), float(v.z)};
    if (ImGui::DragFloat3(label(p).c_str(), f, p.widget.speed, float(p.widget.lo), float(p.widget.hi), p.widget.format)) {
      v = glm::dvec3(f[0], f[1], f[2]);
      changed = true;
    }
  }
  void choice(const ParamInfo& p, int& v) override {
    if (!shown(p)) return;
    if (p.widget.style == Widget::ReadOnly) fixed.push_back(fmt::format("{} = {}", label(p), p.choices[size_t(v)]));
    else if (p.widget.style != Widget::Hidden)
      changed |= ImGui::Combo(p.key, &v, p.choices.data(), int(p.choices.size()));
  }
  // The mesh file and its pins: shown, never edited (a new mesh is a new cloth: Reload).
  void text(const ParamInfo& p, std::string& v) override {
    if (shown(p) && p.widget.style == Widget::ReadOnly) fixed.push_back(fmt::format("{} = {}", label(p), v));
  }
  void indices(const ParamInfo& p, std::vector<int>& v) override {
    if (shown(p) && p.widget.style == Widget::ReadOnly)
      fixed.push_back(fmt::format("{} = {} {}", label(p), v.size(), v.size() == 1 ? "vertex" : "vertices"));
  }
  void grid_indices(const ParamInfo&, GridIndices&, int, int) override {}  // pins: edit the file
  void keyframes(const ParamInfo&, Keyframes&) override {}  // motions: edit the file
  void object(const ParamInfo& p, ObjectRef& o) override {
    // An optional object whose row has a checkbox (wind, gust) can be added and removed live.
    if (o.optional() && p.widget.style == Widget::Checkbox) {
      bool on = o.present();
      if (ImGui::Checkbox(p.key, &on)) {
        o.set_present(on);
        changed = true;
      }
    }
    if (!shown(p) || !o.present()) return;
    ImGui::PushID(p.key);  // the same key may appear in two objects
    o.visit(*this);
    ImGui::PopID();
  }
  // Colliders (Hidden): edit the file. The cloths: the first as a single cloth always was, each
  // further one under a tree node of its own, its read-only rows labelled with its key path.
  void list(const ParamInfo& p, ListRef& l) override {
    if (p.widget.style == Widget::Hidden) return;
    for (size_t i = 0; i < l.size(); ++i) {
      const std::string name = fmt::format("{}[{}]", p.key, i);
      if (i > 0 && !ImGui::TreeNode(name.c_str())) continue;
      MeshProbe probe;
      l.visit(i, probe);
      PanelRows sub(probe.mesh, i == 0 ? prefix_ : prefix_ + name + ".");
      ImGui::PushID(i == 0 ? p.key : name.c_str());  // cloth is the ID of the one cloth, as before
      l.visit(i, sub);
      ImGui::PopID();
      changed |= sub.changed;
      fixed.insert(fixed.end(), sub.fixed.begin(), sub.fixed.end());
      if (i > 0) ImGui::TreePop();
    }
  }

  PanelRows() = default;

 private:
  PanelRows(bool mesh, std::string prefix) : mesh_(mesh), prefix_(std::move(prefix)) {}
  // A row of the other kind of cloth holds only its default: not shown.
  bool shown(const ParamInfo& p) const { return p.shape == Shape::Any || (p.shape == Shape::Mesh) == mesh_; }
  std::string label(const ParamInfo& p) const {
    const char* unit = p.widget.unit ? p.widget.unit : p.unit;
    return prefix_ + (*unit ? fmt::format("{} ({})", p.key, unit) : std::string(p.key));
  }
  bool mesh_ = false;
  std::string prefix_;  // of the read-only rows' labels: "" for the first cloth, "cloth[1]." after
};

void simulation_panel(ViewerState& st) {
  if (!ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) return;
  PanelRows rows;
  visit_rows(st.scene, rows);
  st.parameters_changed |= rows.changed;
  // Collapsed by default, so that the panel is no taller for them.
  if (!rows.fixed.empty() && ImGui::TreeNode("needs a new cloth: edit the scene file, then Reload")) {
    for (const std::string& f : rows.fixed) ImGui::TextDisabled("%s", f.c_str());
    ImGui::TreePop();
  }
  ImGui::TextDisabled("P pause  N step  R reset  Space camera  S screenshot  F1 panels");
  ImGui::TextDisabled("drag: orbit  right/ctrl-drag: pan  wheel: zoom  shift-drag: grab");
  ImGui::TextDisabled("alt-drag a sphere: move it (its keyframes too) in the plane facing you");
}

void appearance_panel(ViewerState& st) {
  if (!ImGui::CollapsingHeader("Appearance")) return;
  int shader = int(st.look.shader);
  if (ImGui::Combo("shader", &shader, kShaderNames.data(), int(kShaderNames.size()))) st.look.shader = ShaderKind(shader);
  ImGui::ColorEdit3("colour", &st.look.color.x);
  ImGui::SliderFloat("normal scaling", &st.look.normal_scaling, 0.f, 20.f);
  ImGui::SliderFloat("height scaling", &st.look.height_scaling, 0.f, 0.1f, "%.3f");
  // Logarithmic: each stop (a doubling) takes the same slider travel.
  ImGui::SliderFloat("exposure", &st.look.exposure, 0.125f, 8.f, "%.2f", ImGuiSliderFlags_Logarithmic);
  ImGui::Checkbox("spheres", &st.look.show_spheres);
  ImGui::SameLine();
  ImGui::Checkbox("planes", &st.look.show_planes);
  ImGui::SameLine();
  ImGui::Checkbox("meshes", &st.look.show_meshes);
  // The demo look (docs/rendering.md); the lit shaders only.
  ImGui::Checkbox("shadows", &st.look.shadows);
  ImGui::SameLine();
  ImGui::Checkbox("ambient occlusion", &st.look.ambient_occlusion);
  ImGui::SameLine();
  ImGui::Checkbox("studio", &st.look.studio);
  if (st.scene.planes.empty()) {
    ImGui::SameLine();
    ImGui::Checkbox("floor", &st.look.floor);
  }
  ImGui::ColorEdit3("back tint", &st.look.back_tint.x);
  if (st.look.shader == ShaderKind::Wireframe) {
    ImGui::Checkbox("structural", &st.look.wire_springs[0]);
    ImGui::SameLine();
    ImGui::Checkbox("shearing", &st.look.wire_springs[1]);
    ImGui::SameLine();
    ImGui::Checkbox("bending", &st.look.wire_springs[2]);
  }
}

void scene_panel(ViewerState& st, const std::filesystem::path& root) {
  if (!ImGui::CollapsingHeader("Scene")) return;
  ImGui::TextWrapped("%s", st.scene.source.c_str());
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (auto& e : std::filesystem::directory_iterator(root / "scenes", ec))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (auto& f : files) {
    if (ImGui::SmallButton(f.stem().string().c_str())) st.open_requested = f.string();
    ImGui::SameLine();
  }
  ImGui::NewLine();
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s", st.path_field.c_str());
  if (ImGui::InputText("path", buf, sizeof buf)) st.path_field = buf;
  if (ImGui::Button("Open")) st.open_requested = st.path_field;
  ImGui::SameLine();
  if (ImGui::Button("Reload")) st.reload_requested = true;
  ImGui::SameLine();
  if (ImGui::Button("Save as")) {
    // Beside the named file first and renamed once complete (output_file.hpp): a scene is
    // never left half written.
    try {
      write_text_replacing(st.path_field, scene_to_json(st.scene));
      st.status = fmt::format("saved {}", st.path_field);
    } catch (const std::exception& e) {
      st.status = fmt::format("not saved: {}", e.what());
    }
  }
  if (!st.status.empty()) ImGui::TextWrapped("%s", st.status.c_str());
}

void stats_panel(const ViewerState& st) {
  if (!ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const ViewerStats& s = st.stats;
  ImGui::Text("%.1f FPS%s", s.fps, st.paused ? "  (paused: P to run)" : "");
  ImGui::Text("simulation %.2f ms/frame, rendering %.2f ms (%s)", s.sim_ms, s.render_ms,
              s.gpu_timers ? "GL timer queries" : "CPU clock + glFinish");
  // What the look costs, pass by pass (zero for a pass the look or the shader leaves out).
  ImGui::Text("  shadow %.1f ms, occlusion %.1f ms, shading %.1f ms", s.passes.shadow_ms, s.passes.occlusion_ms,
              s.passes.shading_ms);
  ImGui::Text("%d particles, %d springs", s.particles, s.springs);
  ImGui::Text("%d dispatches per frame", s.dispatches_per_frame);
  if (s.contacts >= 0) ImGui::Text("%d self-collision contacts", s.contacts);
}

}  // namespace

void draw_panels(ViewerState& st, const std::filesystem::path& root) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(470, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("clothsim");
  if (!st.divergence.empty()) {
    // First, above every panel: the simulation has stopped and says why.
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.45f, 0.35f, 1.f));
    ImGui::TextWrapped("%s", st.divergence.c_str());
    ImGui::PopStyleColor();
    ImGui::Separator();
  }
  ImGui::PushItemWidth(-200.f);  // leave room for the key names as labels
  simulation_panel(st);
  appearance_panel(st);
  scene_panel(st, root);
  stats_panel(st);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace clothsim

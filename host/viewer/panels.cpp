// The viewer's Dear ImGui panels. Labels are the scene JSON key names (one name end to end).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <imgui.h>

#include "viewer_state.hpp"

namespace clothsim {
namespace {

void simulation_panel(ViewerState& st) {
  if (!ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ClothParams& c = st.scene.cloth;
  SimulationParams& s = st.scene.simulation;
  bool changed = false;
  changed |= ImGui::Checkbox("enable_structural", &c.enable_structural);
  changed |= ImGui::Checkbox("enable_shearing", &c.enable_shearing);
  changed |= ImGui::Checkbox("enable_bending", &c.enable_bending);
  // Density is stored in kg/m^2 and shown in g/cm^2 like the classic GUI (1 g/cm^2 = 10 kg/m^2).
  float density_g_cm2 = float(c.density / 10.0);
  if (ImGui::DragFloat("density (g/cm^2)", &density_g_cm2, 0.1f, 0.01f, 1000.f, "%.2f")) {
    c.density = std::max(0.001, double(density_g_cm2) * 10.0);
    changed = true;
  }
  auto drag_double = [&](const char* label, double& v, float speed, double lo, double hi, const char* fmt) {
    float f = float(v);
    if (ImGui::DragFloat(label, &f, speed, float(lo), float(hi), fmt)) {
      v = std::clamp(double(f), lo, hi);
      changed = true;
    }
  };
  drag_double("ks (N/m)", c.ks, 10.f, 0.0, 1e7, "%.0f");
  drag_double("damping (%)", c.damping, 0.01f, 0.0, 100.0, "%.3f");
  drag_double("frames_per_sec", s.frames_per_sec, 1.f, 1.0, 1000.0, "%.0f");
  changed |= ImGui::DragInt("simulation_steps", &s.simulation_steps, 1.f, 1, 1000);
  float g[3] = {float(s.gravity.x), float(s.gravity.y), float(s.gravity.z)};
  if (ImGui::DragFloat3("gravity (m/s^2)", g, 0.05f)) {
    s.gravity = glm::dvec3(g[0], g[1], g[2]);
    changed = true;
  }
  drag_double("max_stretch", s.max_stretch, 0.005f, 0.0, 10.0, "%.3f");
  changed |= ImGui::DragInt("constraint_iterations", &s.constraint_iterations, 0.1f, 0, 100);
  changed |= ImGui::Checkbox("self_collision", &s.self_collision);
  drag_double("thickness (m)", c.thickness, 0.0005f, 1e-4, 1.0, "%.4f");
  s.simulation_steps = std::max(1, s.simulation_steps);
  s.constraint_iterations = std::max(0, s.constraint_iterations);
  st.parameters_changed |= changed;
  ImGui::TextDisabled("P pause  N step  R reset  Space camera  S screenshot  F1 panels");
  ImGui::TextDisabled("drag: orbit  right/ctrl-drag: pan  wheel: zoom  shift-drag: grab");
}

void appearance_panel(ViewerState& st) {
  if (!ImGui::CollapsingHeader("Appearance")) return;
  int shader = int(st.look.shader);
  if (ImGui::Combo("shader", &shader, kShaderNames.data(), int(kShaderNames.size()))) st.look.shader = ShaderKind(shader);
  ImGui::ColorEdit3("colour", &st.look.color.x);
  ImGui::SliderFloat("normal scaling", &st.look.normal_scaling, 0.f, 20.f);
  ImGui::SliderFloat("height scaling", &st.look.height_scaling, 0.f, 0.1f, "%.3f");
  ImGui::Checkbox("spheres", &st.look.show_spheres);
  ImGui::SameLine();
  ImGui::Checkbox("planes", &st.look.show_planes);
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
    std::ofstream out(st.path_field);
    st.status = out && (out << scene_to_json(st.scene)) ? fmt::format("saved {}", st.path_field)
                                                        : fmt::format("cannot write {}", st.path_field);
  }
  if (!st.status.empty()) ImGui::TextWrapped("%s", st.status.c_str());
}

void stats_panel(const ViewerState& st) {
  if (!ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const ViewerStats& s = st.stats;
  ImGui::Text("%.1f FPS%s", s.fps, st.paused ? "  (paused: P to run)" : "");
  ImGui::Text("simulation %.2f ms/frame, rendering %.2f ms (%s)", s.sim_ms, s.render_ms,
              s.gpu_timers ? "GL timer queries" : "CPU clock + glFinish");
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

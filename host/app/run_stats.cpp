#include "run_stats.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "analysis/intersections.hpp"
#include "io/output_file.hpp"

namespace clothsim {
namespace {

// JSON has no NaN or infinity: a non-finite figure is written as null (and "finite": false says why).
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json numbers(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}

}  // namespace

nlohmann::json stats_json(const Scene& scene, const ClothModel& model, Backend& backend, int64_t frames, double wall) {
  const ClothSnapshot snap = backend.snapshot();
  const ClothStats st = measure(scene, model, snap, backend.time());
  const int64_t substeps = frames * scene.simulation.simulation_steps;
  nlohmann::json j;
  j["backend"] = backend.name();
  j["particles"] = model.count();
  j["frames"] = frames;
  j["substeps"] = substeps;
  j["time_s"] = backend.time();
  j["wall_time_s"] = wall;
  j["ms_per_frame"] = frames ? 1e3 * wall / double(frames) : 0.0;
  j["max_stretch"] = number(st.max_stretch_ratio);
  j["p99_stretch"] = number(st.p99_stretch_ratio);
  j["settling_passes"] = backend.stretch_settling_passes();
  j["kinetic_energy_J"] = number(st.kinetic);
  j["gravitational_energy_J"] = number(st.gravitational);
  j["spring_energy_J"] = number(st.spring);
  j["max_speed_m_s"] = number(st.max_speed);
  j["sphere_clearance_m"] = numbers(st.sphere_clearance);
  j["plane_clearance_m"] = numbers(st.plane_clearance);
  j["mesh_clearance_m"] = numbers(st.mesh_clearance);
  j["mesh_inside_masses"] = st.mesh_inside;
  if (st.seam_pairs > 0) {
    j["seam_pairs"] = st.seam_pairs;
    j["max_seam_gap_m"] = number(st.max_seam_gap);
  }
  j["finite"] = st.finite;
  j["self_intersections"] = count_self_intersections(model, snap);
  return j;
}

void print_profile(const PassProfile& profile, int64_t frames, const std::string& clock) {
  const double per_frame = frames > 0 ? 1e3 / double(frames) : 0.0, total = profile.total_seconds();
  fmt::print("profile           {} frames, each pass on its own ({}); ms per frame:\n", frames, clock);
  for (const PassProfile::Row& r : profile.rows())
    fmt::print("  {:32} {:9.2f} ms  {:6.1f} runs/frame  {:5.1f} %\n", r.name, r.seconds * per_frame,
               frames > 0 ? double(r.runs) / double(frames) : 0.0, total > 0 ? 100 * r.seconds / total : 0.0);
  fmt::print("  {:32} {:9.2f} ms\n", "all passes", total * per_frame);
}

nlohmann::json profile_json(const PassProfile& profile, int64_t frames) {
  nlohmann::json j = nlohmann::json::object();
  for (const PassProfile::Row& r : profile.rows()) j[r.name] = frames > 0 ? 1e3 * r.seconds / double(frames) : 0.0;
  return j;
}

void write_stats_json(const std::string& path, const nlohmann::json& json) {
  const std::string text = json.dump(2) + "\n";
  write_text_file(path, [&](std::FILE* f) { std::fputs(text.c_str(), f); });
}

}  // namespace clothsim

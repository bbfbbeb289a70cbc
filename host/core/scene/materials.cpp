#include "scene/materials.hpp"

#include <fmt/format.h>

#include "io/input_file.hpp"

namespace clothsim {
namespace {

// density kg/m^2, stretch [warp, weft] N/m, shear N/m, bending [warp, weft] N·m, compression.
// docs/materials.md, "Presets", cites each.
// A shortened direction's share of its stretch stiffness (docs/materials.md, "compression").
constexpr double kCompression = 1.0;

const MaterialPreset kPresets[] = {
    {"silk", {"", 0.060, {1000, 500}, 15, {1.0e-6, 7.8e-7}, kCompression}},
    {"cotton", {"", 0.125, {5000, 3000}, 56, {1.2e-5, 8.0e-6}, kCompression}},
    {"wool", {"", 0.163, {2500, 2000}, 34, {6.6e-6, 6.6e-6}, kCompression}},
    {"denim", {"", 0.40, {5000, 2000}, 90, {6.0e-5, 4.0e-5}, kCompression}},
    {"leather", {"", 0.55, {1500, 1500}, 500, {2.5e-5, 2.5e-5}, kCompression}},
};

std::string preset_names() {
  std::string out;
  for (const MaterialPreset& p : kPresets) out += fmt::format("{}\"{}\"", out.empty() ? "" : ", ", p.name);
  return out;
}

}  // namespace

std::span<const MaterialPreset> material_presets() { return kPresets; }

void resolve_material(MaterialParams& m, const std::string& source, const std::string& key) {
  const MaterialParams* preset = nullptr;
  if (!m.preset.empty()) {
    for (const MaterialPreset& p : kPresets)
      if (m.preset == p.name) preset = &p.values;
    if (!preset)
      throw SceneError(fmt::format("{}: {}.preset: expected one of {}, got \"{}\"", source, key, preset_names(),
                                   printable(m.preset)));
  }
  auto fill = [&](double& v, double from, const char* name, const char* expected) {
    if (v == 0 && preset) v = from;
    if (!(v > 0))
      throw SceneError(fmt::format("{}: {}.{}: expected {} (or a preset: {}.preset, one of {})", source, key, name,
                                   expected, key, preset_names()));
  };
  fill(m.density, preset ? preset->density : 0, "density", "a density > 0 (kg/m^2)");
  for (int k = 0; k < 2; ++k) {
    fill(m.stretch[size_t(k)], preset ? preset->stretch[size_t(k)] : 0, "stretch", "a stiffness > 0 (N/m)");
    fill(m.bending[size_t(k)], preset ? preset->bending[size_t(k)] : 0, "bending", "a bending rigidity > 0 (N·m)");
  }
  fill(m.shear, preset ? preset->shear : 0, "shear", "a shear stiffness > 0 (N/m)");
  if (m.compression == 0) m.compression = preset ? preset->compression : kCompression;
  if (!(m.compression > 0 && m.compression <= 1))
    throw SceneError(fmt::format("{}: {}.compression: expected a ratio in (0, 1], got {}", source, key, m.compression));
}

}  // namespace clothsim

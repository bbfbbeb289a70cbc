// The fabric presets of cloth.material (docs/materials.md gives each value's source) and the
// loader's resolution of a material: a preset's values under the scene's own.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "scene/scene.hpp"

namespace clothsim {

struct MaterialPreset {
  const char* name;
  MaterialParams values;  // preset empty
};

// silk, cotton, wool, denim, leather: in that order.
std::span<const MaterialPreset> material_presets();

// Fills every value `m` leaves at 0 from its preset and checks the result. Throws SceneError
// naming `key` (e.g. "cloth.material") and the value: an unknown preset, a value left at 0
// without a preset.
void resolve_material(MaterialParams& m, const std::string& source, const std::string& key);

}  // namespace clothsim

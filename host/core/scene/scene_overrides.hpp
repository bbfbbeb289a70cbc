// `--set key.path=value` overrides, applied to the scene JSON before validation so an
// override is checked exactly like the file (docs/design.md §3).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace clothsim {

// Path syntax: dot-separated keys, with [i] to index an array: `cloth.ks`,
// `sphere[0].radius`, `simulation.gravity[1]`. The value is JSON (`500`, `false`,
// `[0, -9.8, 0]`); anything that is not JSON is taken as a string, which validation rejects
// with the key's expected type. Missing objects along the path are created.
//
// `cloth` may be one object or an array of cloths: `cloth.ks` and `cloth[0].ks` edit the first
// cloth either way, `cloth[1].ks` the second of an array. Setting a cloth's `mesh` removes its
// grid keys (width, height, num_width_points, num_height_points, orientation, pinned), so that
// `--set cloth.mesh=flag.obj` turns a grid scene's cloth into a mesh cloth (the path is relative
// to the scene file, like one written in it).
void apply_overrides(nlohmann::json& scene, const std::vector<std::string>& overrides, const std::string& source);

// Deepest nesting of arrays and objects accepted in a scene file or a --set value (a scene
// needs 4: cloth.pinned[k][0]), and of a --set key path. nlohmann parses any depth, but
// dumping or copying a value recurses, so a few tens of thousands of '[' overflowed the stack.
inline constexpr int kMaxJsonDepth = 32;
// nlohmann::json::parse that throws SceneError("<where>: ...") past kMaxJsonDepth levels.
nlohmann::json parse_json_limited(const std::string& text, const std::string& where, bool allow_exceptions);

// `text` for a message: at most `max` bytes, the last three "..." when it was cut, and never
// cut inside a UTF-8 sequence.
std::string abbreviate(const std::string& text, size_t max);

}  // namespace clothsim

// Assimp 5.2 (Debian bookworm's) crashes reading a glTF whose skin has no inverseBindMatrices
// (which glTF allows: they default to the identity): a null dereference in its importer. This
// reads a glTF's JSON first (a .gltf file, or a .glb's JSON chunk) and names that case, so it is
// refused with a message instead of taking the process down.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace clothsim {

// What is wrong with `file` (of `size` bytes) for Assimp as a glTF, or nullopt when it is sound
// or is not a glTF at all (by its extension): other formats are left to Assimp.
std::optional<std::string> gltf_problem(const std::filesystem::path& file, uint64_t size);

}  // namespace clothsim

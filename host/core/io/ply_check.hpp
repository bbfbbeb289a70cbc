// A PLY's header states how many vertices and faces follow, and Assimp allocates what it
// states before reading them: a 200-byte file claiming 10^9 vertices asked for 17 GB. This
// reads the header first and checks its counts against the file's size; for an ASCII PLY it
// also checks each data line against the header (a truncated file must not load as a cloth
// with a face line taken for a vertex), for a binary one that the data is all there.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace clothsim {

// What is wrong with `file` (of `size` bytes) as a PLY, or nullopt when it is sound or is not
// a PLY at all (it does not start with "ply"): other formats are left to Assimp.
std::optional<std::string> ply_problem(const std::filesystem::path& file, uint64_t size);

}  // namespace clothsim

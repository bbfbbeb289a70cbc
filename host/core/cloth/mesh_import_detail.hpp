// What mesh_import.cpp and obj_positions.cpp share: the file being imported, for messages.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/vec3.hpp>

#include "io/input_file.hpp"
#include "scene/scene.hpp"

namespace clothsim::mesh_import_detail {

struct Context {
  const std::filesystem::path& file;
  const std::string& what;

  [[noreturn]] void fail(const std::string& problem) const {
    throw SceneError(fmt::format("{}: {}: {}", what, printable(file.string()), problem));
  }
  void warn(const std::string& problem) const {
    fmt::print(stderr, "warning: {}: {}: {}\n", what, printable(file.string()), printable(problem));
  }
};

// The positions of an OBJ's `v` lines, in file order, read as doubles (locale-independent).
std::vector<glm::dvec3> read_obj_positions(const Context& cx);

}  // namespace clothsim::mesh_import_detail

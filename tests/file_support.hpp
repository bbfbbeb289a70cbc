// Small file chores of the tests that check what clothsim writes: a file's bytes, writing one,
// an OBJ's vertices, a folder's names.
#pragma once

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace clothsim::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void put_file(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

// The `v x y z` lines of an OBJ, in order.
inline std::vector<glm::dvec3> read_obj_vertices(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<glm::dvec3> v;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream ss(line.substr(2));
    glm::dvec3 p;
    ss >> p.x >> p.y >> p.z;
    v.push_back(p);
  }
  return v;
}

// The names in a folder (not recursive).
inline std::set<std::string> listing(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

}  // namespace clothsim::test

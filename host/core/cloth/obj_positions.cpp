// An OBJ's own vertex order: its `v` lines, read without Assimp (mesh_import.hpp says why).
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "cloth/mesh_import.hpp"
#include "cloth/mesh_import_detail.hpp"

namespace clothsim::mesh_import_detail {

std::vector<glm::dvec3> read_obj_positions(const Context& cx) {
  std::ifstream in(cx.file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<glm::dvec3> out;
  size_t line_no = 0;
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find_first_of("\r\n", pos);  // \n, \r\n and a lone \r end a line
    if (end == std::string::npos) end = text.size();
    ++line_no;
    const char* p = text.data() + pos;
    const char* e = text.data() + end;
    pos = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    if (line_no == 1 && e - p >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3;  // UTF-8 BOM
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    if (e - p < 2 || p[0] != 'v' || (p[1] != ' ' && p[1] != '\t')) continue;
    ++p;
    double v[7];
    int n = 0;
    for (;;) {
      while (p < e && (*p == ' ' || *p == '\t')) ++p;
      if (p == e || *p == '#') break;
      const char* tok = p;
      while (p < e && *p != ' ' && *p != '\t') ++p;
      const char* start = (*tok == '+') ? tok + 1 : tok;  // from_chars takes no '+'
      double value = 0;
      auto [ptr, ec] = std::from_chars(start, p, value);
      if (ec != std::errc() || ptr != p)
        cx.fail(fmt::format("line {}: cannot read \"{}\" as a number of a `v` line", line_no, std::string(tok, p)));
      if (n < 7) v[n] = value;
      ++n;
    }
    // As Assimp: 3 numbers are x y z, 4 are homogeneous (x/w, y/w, z/w), 6 are x y z r g b.
    // It skips other counts silently, which shifts every later index: refuse them instead.
    if (n != 3 && n != 4 && n != 6)
      cx.fail(fmt::format("line {}: a `v` line with {} numbers (expected 3, 4 or 6)", line_no, n));
    glm::dvec3 q(v[0], v[1], v[2]);
    if (n == 4) q /= v[3];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      cx.fail(fmt::format("vertex {} (line {}) has a non-finite coordinate ({}, {}, {})", out.size(), line_no, q.x, q.y, q.z));
    out.push_back(q);
    if (out.size() > kMaxMeshVertices)
      cx.fail(fmt::format("more than {} vertices (the largest cloth accepted)", kMaxMeshVertices));
  }
  return out;
}

}  // namespace clothsim::mesh_import_detail

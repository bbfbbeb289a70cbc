// The CS184 grid as a builder of the cloth model (docs/design.md §1 "Cloth construction"): particles
// row-major, two triangles per cell, the springs of kDirections with the grid's own twelve
// colours and the classic gather order, so the classic scenes compute what they always did.
#include <cmath>

#include "cloth/spring_grid.hpp"

namespace clothsim {

PartSprings append_grid(ClothModel& m, const ClothParams& p, uint32_t material, uint32_t seed) {
  const int nw = p.num_width_points, nh = p.num_height_points;
  const uint32_t base = uint32_t(m.count());
  auto index = [&](int x, int y) { return base + uint32_t(y * nw + x); };
  const double sx = p.width / (nw - 1), sy = p.height / (nh - 1);
  const double jitter = jitter_amplitude(std::min(sx, sy));
  const double area = p.width * p.height / (double(nw) * double(nh));
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) {
      // The jitter hashes the index within this cloth, so a grid is the same cloth wherever it
      // comes in the scene. The classic horizontal grid is flat; with a seed it is jittered too.
      const uint32_t local = uint32_t(y * nw + x);
      m.initial.push_back(p.orientation == Orientation::Horizontal
                              ? glm::dvec3(x * sx, 1.0 + (seed ? vertical_offset(local, jitter, seed) : 0.0), y * sy)
                              : glm::dvec3(x * sx, y * sy, vertical_offset(local, jitter, seed)));
      m.uv.push_back({double(x) / (nw - 1), double(y) / (nh - 1)});
      // A material's mass is its density times the particle's own share of the cloth (a
      // quarter cell at a corner, half at an edge); the CS184 grid spreads it evenly.
      m.area.push_back(p.material ? sx * sy * (x == 0 || x == nw - 1 ? 0.5 : 1.0) * (y == 0 || y == nh - 1 ? 0.5 : 1.0)
                                  : area);
      m.pinned.push_back(0);
      m.material.push_back(material);
      m.tangent_ends.push_back({index(x > 0 ? x - 1 : x, y), index(x + 1 < nw ? x + 1 : x, y)});
    }
  for (auto& pin : p.pinned) m.pinned[index(pin[0], pin[1])] = 1;

  for (int y = 0; y + 1 < nh; ++y)
    for (int x = 0; x + 1 < nw; ++x) {
      const uint32_t a = index(x, y), b = index(x + 1, y), c = index(x, y + 1), d = index(x + 1, y + 1);
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({b, c, d});
    }

  // The spring of direction d stored at (x, y), and its number within the part (-1: none).
  PartSprings out;
  std::vector<std::array<int32_t, NUM_DIRECTIONS>> id(size_t(nw) * nh);
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x)
      for (int d = 0; d < NUM_DIRECTIONS; ++d) {
        const Direction& dir = kDirections[d];
        const int x2 = x + dir.dx, y2 = y + dir.dy;
        id[size_t(y) * nw + x][d] = -1;
        if (!in_grid(x2, y2, nw, nh)) continue;
        const glm::dvec3 e = m.initial[index(x2, y2)] - m.initial[index(x, y)];
        id[size_t(y) * nw + x][d] = int32_t(out.springs.size());
        out.springs.push_back({index(x, y), index(x2, y2), std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z), dir.type,
                               material});
        // Colours 2d, 2d + 1 of the grid; four per type.
        out.colour.push_back(uint32_t(spring_colour(d, x, y) - 4 * int(dir.type)));
      }
  // kGatherOrder: per direction the spring stored here, then the one stored behind.
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) {
      for (const SpringRef& ref : kGatherOrder) {
        const Direction& dir = kDirections[ref.direction];
        const int xs = ref.sign > 0 ? x : x - dir.dx, ys = ref.sign > 0 ? y : y - dir.dy;
        if (!in_grid(xs, ys, nw, nh)) continue;
        const int32_t s = id[size_t(ys) * nw + xs][ref.direction];
        if (s >= 0) out.gather.push_back(uint32_t(s));
      }
      out.gather.push_back(kEndOfList);
    }
  return out;
}

}  // namespace clothsim

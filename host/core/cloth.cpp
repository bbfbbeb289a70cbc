#include "cloth.hpp"

#include <algorithm>
#include <cmath>

namespace clothsim {

double vertical_offset(uint32_t i, double amplitude) {
  // splitmix64 finaliser: a well-mixed, portable hash of the index.
  uint64_t z = uint64_t(i) + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  double u = double(z >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
  return (2.0 * u - 1.0) * amplitude;
}

double jitter_amplitude(double spacing) {
  // The classic +-1 mm, but never more than 5 % of the spacing: on a fine cloth 1 mm would be
  // a crumple baked into the rest lengths. At the classic spacing (1/49 m) 5 % is 1.02 mm, so
  // the classic scenes keep exactly 1e-3.
  return std::min(1e-3, 0.05 * spacing);
}

double particle_mass(const ClothParams& p) {
  return p.width * p.height * p.density / (double(p.num_width_points) * double(p.num_height_points));
}

ClothModel build_cloth(const ClothParams& p) {
  ClothModel m;
  m.nw = p.num_width_points;
  m.nh = p.num_height_points;
  const int n = m.count();
  m.mass = particle_mass(p);
  const double sx = p.width / (m.nw - 1), sy = p.height / (m.nh - 1);
  const double jitter = jitter_amplitude(std::min(sx, sy));

  m.initial.resize(n);
  m.uv.resize(n);
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x) {
      int i = m.index(x, y);
      m.initial[i] = p.orientation == Orientation::Horizontal
                         ? glm::dvec3(x * sx, 1.0, y * sy)
                         : glm::dvec3(x * sx, y * sy, vertical_offset(uint32_t(i), jitter));
      m.uv[i] = {double(x) / (m.nw - 1), double(y) / (m.nh - 1)};
    }

  m.pinned.assign(n, 0);
  for (auto& pin : p.pinned) m.pinned[m.index(pin[0], pin[1])] = 1;

  m.rest.assign(n, {});
  for (int y = 0; y < m.nh; ++y)
    for (int x = 0; x < m.nw; ++x)
      for (int d = 0; d < NUM_DIRECTIONS; ++d) {
        int x2 = x + kDirections[d].dx, y2 = y + kDirections[d].dy;
        if (!in_grid(x2, y2, m.nw, m.nh)) continue;
        glm::dvec3 e = m.initial[m.index(x2, y2)] - m.initial[m.index(x, y)];
        m.rest[m.index(x, y)][d] = std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
      }

  for (int y = 0; y + 1 < m.nh; ++y)
    for (int x = 0; x + 1 < m.nw; ++x) {
      uint32_t a = m.index(x, y), b = m.index(x + 1, y), c = m.index(x, y + 1), d = m.index(x + 1, y + 1);
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({b, c, d});
    }
  build_tethers(m);
  return m;
}

}  // namespace clothsim

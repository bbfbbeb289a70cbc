// Long-range attachments (Kim, Chentanez, Müller 2012, "Long Range Attachments: A Method to
// Simulate Inextensible Clothing in Computer Games"): every particle is tied to its nearest
// pin along the rest cloth, so that a local solver cannot let a large cloth sag further than
// that distance allows however slowly its constraints converge.
#include "cloth/cloth.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <queue>

namespace clothsim {

void build_tethers(ClothModel& m) {
  const int n = m.count();
  m.tether_pin.assign(n, -1);
  m.tether_rest.assign(n, 0.0);
  // Dijkstra from every pin at once over the structural and shearing springs (both ways, in
  // each particle's gather order): the shortest path along the rest cloth, which is never
  // shorter than the straight line, so a tether never pulls a mass that the cloth itself would
  // hold. Pins of one cloth never tether another: the springs do not cross.
  using Item = std::pair<double, int>;  // distance, particle
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  for (int i = 0; i < n; ++i)
    if (m.pinned[i]) {
      m.tether_pin[i] = i;
      open.push({0.0, i});
    }
  std::vector<uint8_t> done(n, 0);
  while (!open.empty()) {
    const auto [dist, i] = open.top();
    open.pop();
    if (done[i]) continue;
    done[i] = 1;
    m.tether_rest[i] = dist;
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
      const Spring& s = m.springs[m.gather[g]];
      if (s.type == SpringType::Bending || s.type == SpringType::Seam) continue;
      const int j = int(s.i) == i ? int(s.j) : int(s.i);
      if (done[j]) continue;
      const double next = dist + s.rest;
      if (m.tether_pin[j] < 0 || next < m.tether_rest[j]) {
        m.tether_pin[j] = m.tether_pin[i];
        m.tether_rest[j] = next;
        open.push({next, j});
      }
    }
  }
  // The length: on a grid (a flat rectangle) the straight rest distance to that pin, which is
  // the distance along the flat cloth (Kim et al. use the rest-pose distance); the path over
  // the 8-neighbour springs is up to 8 % longer (1 / cos 22.5°), so a tether of that length
  // let a cloth stretch 8 % before it held. A mesh may be curved or have holes, where the
  // straight line is shorter than the cloth: it keeps the path along its edges, an upper bound.
  for (const ClothPart& part : m.parts) {
    if (part.nw == 0) continue;
    for (uint32_t i = part.first; i < part.first + part.count; ++i)
      if (const int pin = m.tether_pin[i]; pin >= 0 && !m.pinned[i])
        m.tether_rest[i] = glm::distance(m.initial[i], m.initial[pin]);
  }
  // Pins need no tether.
  for (int i = 0; i < n; ++i)
    if (m.pinned[i]) m.tether_pin[i] = -1;
}

}  // namespace clothsim

// Long-range attachments (Kim, Chentanez, Müller 2012, "Long Range Attachments: A Method to
// Simulate Inextensible Clothing in Computer Games"): every particle is tied to its nearest
// pin, by geodesic distance over the rest cloth, so that a local solver cannot let a large
// cloth sag further than that distance allows however slowly its constraints converge.
#include "cloth.hpp"

#include <cmath>
#include <queue>

namespace clothsim {

void build_tethers(ClothModel& m) {
  const int n = m.count();
  m.tether_pin.assign(n, -1);
  m.tether_rest.assign(n, 0.0);
  // Dijkstra from every pin at once over the structural and shearing springs (both ways): the
  // shortest path along the rest cloth, which is never shorter than the straight line, so a
  // tether never pulls a mass that the cloth itself would hold.
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
    const int x = i % m.nw, y = i / m.nw;
    for (int d = DIR_RIGHT; d <= DIR_DIAG_DOWN_LEFT; ++d)
      for (int sign : {1, -1}) {
        const int x2 = x + sign * kDirections[d].dx, y2 = y + sign * kDirections[d].dy;
        if (!in_grid(x2, y2, m.nw, m.nh)) continue;
        const int j = m.index(x2, y2);
        if (done[j]) continue;
        const double length = m.rest[sign > 0 ? i : j][d];
        const double next = dist + length;
        if (m.tether_pin[j] < 0 || next < m.tether_rest[j]) {
          m.tether_pin[j] = m.tether_pin[i];
          m.tether_rest[j] = next;
          open.push({next, j});
        }
      }
  }
  // Pins need no tether.
  for (int i = 0; i < n; ++i)
    if (m.pinned[i]) m.tether_pin[i] = -1;
}

}  // namespace clothsim

#include "contacts.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "reference/spatial_hash.hpp"

namespace clothsim {

int count_self_contacts(const std::vector<glm::vec4>& pos, const Constants<float>& c) {
  // The reference's hash and neighbour visit (host/core/reference/spatial_hash.hpp), so the panel counts
  // exactly the pairs collide_self pushes apart.
  SpatialHash h = make_spatial_hash(uint32_t(pos.size()));
  const float inv = c.inv_cell, contact = c.contact_distance;
  build_spatial_hash(pos, inv, h);
  int pairs = 0;
  for (uint32_t i = 0; i < pos.size(); ++i)
    for_each_neighbour(h, pos, inv, cell_of(pos[i], inv), [&](uint32_t j) {
      // Each pair once (j > i).
      if (j > i && glm::length(glm::vec3(pos[i]) - glm::vec3(pos[j])) < contact) ++pairs;
    });
  return pairs;
}

}  // namespace clothsim

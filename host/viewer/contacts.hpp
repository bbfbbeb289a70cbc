// Self-collision contacts of a cloth state (pairs closer than the contact distance), found
// with the same hashed grid as the reference; the viewer's Stats panel shows the count.
#pragma once

#include <vector>

#include <glm/vec4.hpp>

#include "reference/reference.hpp"

namespace clothsim {

int count_self_contacts(const std::vector<glm::vec4>& positions, const Constants<float>& c);

}  // namespace clothsim

// Shared by the reference's pass files, not part of its interface.
#pragma once

#include "reference.hpp"

namespace clothsim {

// One particle against every sphere, then every plane (reference_collisions.cpp). With
// `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out of xpbd's constraint pass.
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction);


}  // namespace clothsim

// Shared by the reference's pass files, not part of its interface.
#pragma once

#include "reference.hpp"

namespace clothsim {

// One particle against every sphere, then every plane (reference_collisions.cpp). With
// `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out of xpbd's constraint pass.
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction);
// A mass deeper than 0.1 mm inside a sphere, or behind a plane's front, goes back to the
// surface (a plane's: its surface offset on the front), without friction; otherwise nothing.
template <class R> void keep_out_of_colliders(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d);


}  // namespace clothsim

// Running out of host memory is too large an input (exit 2), like a grid too large for the
// GPU: the big allocations translate std::bad_alloc into this, naming what they allocated and
// how much, and main() maps any other std::bad_alloc to exit 2 as well.
#pragma once

#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace clothsim {

struct HostOutOfMemory : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// allocate(), with a std::bad_alloc turned into HostOutOfMemory naming `what` and `bytes`.
template <class F>
auto allocating(const std::string& what, uint64_t bytes, F&& allocate) -> decltype(allocate()) {
  try {
    return allocate();
  } catch (const std::bad_alloc&) {
    throw HostOutOfMemory(fmt::format("out of host memory allocating {} ({:.1f} MiB): use fewer points "
                                      "(cloth.num_width_points, cloth.num_height_points) or a smaller mesh",
                                      what, double(bytes) / (1 << 20)));
  }
}

}  // namespace clothsim

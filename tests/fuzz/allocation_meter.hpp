// "No allocation larger than the input justifies", checked on every input of the state and
// PC2 fuzz targets: while an AllocationMeter lives, the bytes this thread allocates are counted,
// and the allocation that takes them past the meter's limit aborts at once, with the sizes and
// (under libFuzzer) the stack of the allocation. A size taken from a header and allocated
// before it is checked against the file is caught this way even when the allocation succeeds.
//
// How it counts: with AddressSanitizer (the libFuzzer targets, scripts/fuzz; the sanitizer
// build, scripts/test-sanitizers), through the sanitizer allocator's malloc hook: malloc, new,
// vectors, strings. Elsewhere (the replay in every other build) by replacing the global
// operator new(size_t), which vectors and strings allocate through (plain malloc is not seen).
#pragma once

#include <cstdint>
#include <string>

namespace clothsim::fuzz {

// Not nested: one meter per thread at a time.
class AllocationMeter {
 public:
  // `what` names the reader and its input in the message.
  AllocationMeter(uint64_t limit_bytes, std::string what);
  ~AllocationMeter();
  AllocationMeter(const AllocationMeter&) = delete;
  AllocationMeter& operator=(const AllocationMeter&) = delete;
};

}  // namespace clothsim::fuzz

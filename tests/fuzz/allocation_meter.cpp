#include "allocation_meter.hpp"

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <utility>

// gcc's and clang's AddressSanitizer each define one of these.
#if defined(__SANITIZE_ADDRESS__)
#define CLOTHSIM_HAVE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLOTHSIM_HAVE_ASAN 1
#endif
#endif

#ifdef CLOTHSIM_HAVE_ASAN
// From <sanitizer/allocator_interface.h>, which gcc does not ship; both runtimes export it.
// Up to five hook pairs may be installed (libFuzzer installs one of its own).
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*, size_t),
                                                         void (*free_hook)(const volatile void*));
#endif

namespace clothsim::fuzz {
namespace {

// Per thread, so that libFuzzer's RSS-watching thread is never counted.
thread_local bool t_counting = false;
thread_local uint64_t t_bytes = 0, t_limit = 0;
thread_local std::string t_what;

// Counts `n` more bytes; past the limit, stops counting (the message allocates) and aborts.
void count(size_t n) {
  if (!t_counting) return;
  t_bytes += n;
  if (t_bytes <= t_limit) return;
  t_counting = false;
  std::fprintf(stderr, "fuzz: PROPERTY VIOLATED: %s allocated %llu bytes (an allocation of %zu), more than the %llu "
               "its input justifies\n", t_what.c_str(), (unsigned long long)t_bytes, n, (unsigned long long)t_limit);
  std::fflush(stderr);
  std::abort();
}

#ifdef CLOTHSIM_HAVE_ASAN
void on_malloc(const volatile void*, size_t n) { count(n); }
void on_free(const volatile void*) {}

[[maybe_unused]] const bool installed = [] {
  if (__sanitizer_install_malloc_and_free_hooks(on_malloc, on_free)) return true;
  std::fprintf(stderr, "fuzz: cannot install the allocation meter's malloc hook\n");
  std::abort();
}();
#endif

}  // namespace

AllocationMeter::AllocationMeter(uint64_t limit_bytes, std::string what) {
  t_what = std::move(what);  // allocates nothing
  t_bytes = 0;
  t_limit = limit_bytes;
  t_counting = true;
}

AllocationMeter::~AllocationMeter() {
  t_counting = false;
}

}  // namespace clothsim::fuzz

#ifndef CLOTHSIM_HAVE_ASAN
// Without a sanitizer's hook: every operator new of the program comes here. libstdc++'s other
// forms (array, nothrow, sized) call this one, and its operator delete frees with free().
void* operator new(std::size_t n) {
  clothsim::fuzz::count(n);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
#endif

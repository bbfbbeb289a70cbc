// What lets one file be compiled as GLSL and as C++ (spatial_hash.glsl):
// GLSL's scalar type names and a function qualifier that makes a C++ definition inline and
// constexpr. Write shared functions with `SHARED` in front, GLSL constructor casts (uint(x),
// int(x)), and only what both languages mean the same by (32-bit wrap-around uint arithmetic,
// ternaries instead of switch, no arrays).
#ifndef CLOTHSIM_SHARED_GLSL
#define CLOTHSIM_SHARED_GLSL

#ifdef __cplusplus
#include <cstdint>
namespace clothsim::shared {
using uint = uint32_t;
}
#define SHARED inline constexpr
#define SHARED_BEGIN namespace clothsim::shared {
#define SHARED_END }
#else
#define SHARED
#define SHARED_BEGIN
#define SHARED_END
#endif

#endif

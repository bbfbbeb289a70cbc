// The dialect that lets one file be compiled as GLSL and as C++ (every file of compute/shared/
// and compute/spatial_hash.glsl; the shaders include them, and so does the CPU reference in
// host/core/reference). Write only what both languages mean the same by:
//  - integer functions: `SHARED` in front (C++: inline constexpr), GLSL constructor casts
//    (uint(x), int(x)), 32-bit wrap-around uint arithmetic;
//  - floating-point formulas: `SHARED_FN` in front (C++: a template on the scalar REAL, so the
//    reference runs them in float and in double), the types REAL, VEC3, VEC4, INOUT(T) and
//    OUT(T) for parameters, PARAMS for the step's parameter block (GLSL: the StepParams value
//    `params`; C++: the reference's Constants, whose base is layout::StepParamsT<REAL>) so that
//    a formula reads the fields it needs itself, PRECISE on every rounded temporary (GLSL's `precise`: no fused
//    multiply-add; C++ builds with -ffp-contract=off), literals as REAL(0.5), and only the
//    built-ins brought in below for C++;
//  - ternaries instead of switch, no arrays, no swizzles (.xyz), no GLSL vector relations.
// tests/tools/check_shared_dialect.py checks these rules; tests/test_shared_dialect.cpp compiles
// every shared file for float and double with the strictest warnings.
#ifndef CLOTHSIM_SHARED_DIALECT_GLSL
#define CLOTHSIM_SHARED_DIALECT_GLSL

#ifdef __cplusplus
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "../layout.glsl"

namespace clothsim::shared {
using uint = uint32_t;
// GLSL's built-ins, as the reference has always computed them (std::min(a, b) is b < a ? b : a).
using std::abs;
using std::ceil;
using std::floor;
using std::sqrt;
template <class T> inline T min(T a, T b) { return std::min(a, b); }
// A float's bits and back (the divergence guard's ordered bits); F32 is float in both languages,
// for the few formulas on a float's bits that no double version can mean.
using F32 = float;
inline constexpr uint floatBitsToUint(F32 f) { return std::bit_cast<uint>(f); }
inline constexpr F32 uintBitsToFloat(uint u) { return std::bit_cast<F32>(u); }
template <class T> inline T max(T a, T b) { return std::max(a, b); }
// Whether any component is not zero (GLSL: any(notEqual(v, vec3(0.0)))).
template <class REAL> inline bool nonzero3(const glm::vec<3, REAL>& v) { return v != glm::vec<3, REAL>(0); }
}  // namespace clothsim::shared

#define SHARED inline constexpr
#define SHARED_FN template <class REAL> inline
// A formula the sweep calls per entry of a long gather, inlined into it by force: g++ keeps a
// call to a function this long, whose cost the CPU reference then pays per entry.
#define SHARED_FN_INLINE template <class REAL> [[gnu::always_inline]] inline
#define SHARED_BEGIN namespace clothsim::shared {
#define SHARED_END }
#define VEC3 glm::vec<3, REAL>
#define VEC4 glm::vec<4, REAL>
#define INOUT(T) T&
#define OUT(T) T&
#define PARAMS const layout::StepParamsT<REAL>&
#define PRECISE
#else
#define SHARED
#define SHARED_FN
#define SHARED_FN_INLINE
#define SHARED_BEGIN
#define SHARED_END
#define REAL float
#define VEC3 vec3
#define VEC4 vec4
#define INOUT(T) inout T
#define OUT(T) out T
#define PARAMS StepParams  // the shader includes layout.glsl first
#define PRECISE precise
#define F32 float
bool nonzero3(vec3 v) { return any(notEqual(v, vec3(0.0))); }
#endif

#endif

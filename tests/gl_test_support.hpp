// The GPU test tier: one shared headless OpenGL 4.3 context per test process. Without one,
// a test says why and skips, unless CLOTHSIM_REQUIRE_GPU=1 (set by CI) makes that a failure.
// Catch2 v2 has no skip of its own: REQUIRE_GL_CONTEXT records it, and the tier's main
// (gpu_test_main.cpp) exits 77 when every test case that ran was skipped, which ctest reports
// as Not Run (SKIP_RETURN_CODE 77 in tests/CMakeLists.txt).
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <memory>
#include <string>

#include "context.hpp"
#include "debug_output.hpp"

namespace clothsim::test {

struct GlTestContext {
  std::unique_ptr<gl::GlContext> context;  // null when none could be made
  std::string why_not;                     // then: the reason
  bool available() const { return context != nullptr; }
};

// Made on first use (a debug context, KHR_debug errors collected) and current from then on.
GlTestContext& gl_test_context();

bool gpu_required();  // CLOTHSIM_REQUIRE_GPU=1

// What REQUIRE_GL_CONTEXT saw in the running test case; gpu_test_main.cpp resets it when a
// test case starts and reads it when it ends.
struct TestCaseGlState {
  bool checked = false;  // REQUIRE_GL_CONTEXT ran (every [gpu] test case must call it)
  bool skipped = false;  // and found no context, so the test case returned without testing
};
TestCaseGlState& current_test_case_gl_state();

// A file of the source tree, e.g. source_path("tests/shaders/double_values.comp").
std::filesystem::path source_path(const std::string& relative);

// All collected GL errors as one message, and forgets them.
std::string take_gl_errors();

}  // namespace clothsim::test

// First line of every GPU test (tagged [gpu]): skips (or fails under CLOTHSIM_REQUIRE_GPU=1)
// without a context, and forgets GL errors left by earlier tests so each test sees only its own.
#define REQUIRE_GL_CONTEXT()                                                                 \
  do {                                                                                       \
    auto& gl_test_context_ = ::clothsim::test::gl_test_context();                            \
    ::clothsim::test::current_test_case_gl_state().checked = true;                           \
    if (!gl_test_context_.available()) {                                                     \
      if (::clothsim::test::gpu_required()) {                                                \
        FAIL("no OpenGL 4.3 context (CLOTHSIM_REQUIRE_GPU=1): " << gl_test_context_.why_not); \
      }                                                                                      \
      WARN("skipped: no OpenGL 4.3 context: " << gl_test_context_.why_not);                  \
      ::clothsim::test::current_test_case_gl_state().skipped = true;                         \
      return;                                                                                \
    }                                                                                        \
    ::clothsim::test::take_gl_errors();                                                      \
  } while (false)

// Last line of every GPU test: the driver reported no error through KHR_debug or glGetError.
#define CHECK_NO_GL_ERRORS()                          \
  do {                                                \
    const std::string gl_errors_ = ::clothsim::test::take_gl_errors(); \
    INFO(gl_errors_);                                 \
    CHECK(gl_errors_.empty());                        \
  } while (false)

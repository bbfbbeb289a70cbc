#include "gl_test_support.hpp"

#include <cstdlib>

namespace clothsim::test {

GlTestContext& gl_test_context() {
  static GlTestContext shared = [] {
    GlTestContext made;
    made.context = gl::create_headless_context(&made.why_not, {.debug = true});
    if (made.context) gl::enable_debug_output(gl::DebugMode::Errors);
    return made;
  }();
  return shared;
}

bool gpu_required() {
  const char* value = std::getenv("CLOTHSIM_REQUIRE_GPU");
  return value && std::string(value) == "1";
}

TestCaseGlState& current_test_case_gl_state() {
  static TestCaseGlState state;
  return state;
}

std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(CLOTHSIM_SOURCE_DIR) / relative;
}

std::string take_gl_errors() {
  std::string text;
  for (const std::string& error : gl::gl_errors_since_last_check()) text += error + "\n";
  return text;
}

}  // namespace clothsim::test

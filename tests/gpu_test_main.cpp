// The GPU tier's main. Catch2 v2 cannot skip a test: without an OpenGL 4.3 context a test
// case's REQUIRE_GL_CONTEXT() warns with the reason and returns, which Catch counts as passed.
// So that a machine without OpenGL is never told the GPU tier passed, this main turns a run in
// which every test case skipped into exit code 77, and ctest, which runs one test case per
// process (catch_discover_tests), reports it as Not Run (SKIP_RETURN_CODE 77).
//
// Exit status, also when run by hand with several test cases:
//   - a failure (CLOTHSIM_REQUIRE_GPU=1 without a context included): Catch's own, non-zero;
//   - a [gpu] test case that never called REQUIRE_GL_CONTEXT(), or one that called it without
//     the [gpu] tag (tests/CMakeLists.txt registers [gpu] as the GPU tier, the rest as CPU):
//     1, naming it, so that the split stays honest;
//   - every test case that ran skipped: 77;
//   - otherwise 0, with a line saying how many skipped if some did (a mixed run has tested
//     something, and a filter that matched a test needing no context must still be able to
//     pass).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "gl_test_support.hpp"

namespace {

struct Tally {
  int ran = 0;
  int skipped = 0;
  std::vector<std::string> unchecked;  // [gpu] test cases that never checked for a context
  std::vector<std::string> untagged;   // test cases that checked without the [gpu] tag
};

Tally& tally() {
  static Tally t;
  return t;
}

bool tagged_gpu(const Catch::TestCaseInfo& info) {
  return std::find(info.lcaseTags.begin(), info.lcaseTags.end(), "gpu") != info.lcaseTags.end();
}

struct GlSkipListener : Catch::TestEventListenerBase {
  using TestEventListenerBase::TestEventListenerBase;

  void testCaseStarting(const Catch::TestCaseInfo& info) override {
    TestEventListenerBase::testCaseStarting(info);
    clothsim::test::current_test_case_gl_state() = {};
  }

  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    const clothsim::test::TestCaseGlState& state = clothsim::test::current_test_case_gl_state();
    Tally& t = tally();
    ++t.ran;
    if (state.skipped) ++t.skipped;
    const bool gpu = tagged_gpu(stats.testInfo);
    if (gpu && !state.checked) t.unchecked.push_back(stats.testInfo.name);
    if (!gpu && state.checked) t.untagged.push_back(stats.testInfo.name);
    TestEventListenerBase::testCaseEnded(stats);
  }
};

}  // namespace

CATCH_REGISTER_LISTENER(GlSkipListener)

int main(int argc, char* argv[]) {
  Catch::Session session;
  if (const int usage = session.applyCommandLine(argc, argv); usage != 0) return usage;
  const int failed = session.run();
  const Tally& t = tally();
  for (const std::string& name : t.unchecked)
    std::cout << "error: test case \"" << name << "\" is tagged [gpu] but never calls REQUIRE_GL_CONTEXT()\n";
  for (const std::string& name : t.untagged)
    std::cout << "error: test case \"" << name << "\" calls REQUIRE_GL_CONTEXT() but is not tagged [gpu]\n";
  if (failed != 0) return failed;
  if (!t.unchecked.empty() || !t.untagged.empty()) return 1;
  if (t.skipped == 0) return 0;
  const std::string& why = clothsim::test::gl_test_context().why_not;
  if (t.skipped == t.ran) {
    std::cout << "skipped: all " << t.ran << " test case(s) that ran need an OpenGL 4.3 context and none could be made"
              << " (exit 77, which ctest reports as Not Run): " << why << "\n";
    return 77;
  }
  std::cout << "note: " << t.skipped << " of " << t.ran
            << " test cases were skipped, no OpenGL 4.3 context: " << why << "\n";
  return 0;
}

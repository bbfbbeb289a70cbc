// clothsim_gl_probe: can an OpenGL 4.3 context be made here, the way clothsim makes one
// (gl::create_headless_context, as require_headless_context in host/app/backend_factory.cpp)?
// Exit 0 and print how it was made, or exit 3 (clothsim's "no OpenGL 4.3 context") and print
// why not. tests/tools/gpu_test.sh runs it before each command-level GPU-tier test, so that
// such a test is skipped with the reason instead of failing (or passing) for want of OpenGL.
#include <iostream>
#include <string>

#include "context.hpp"

int main() {
  std::string why;
  const auto context = clothsim::gl::create_headless_context(&why);
  if (!context) {
    std::cout << why << "\n";
    return 3;
  }
  std::cout << context->description() << ": " << clothsim::gl::gl_renderer_string() << ", OpenGL "
            << clothsim::gl::gl_version_string() << "\n";
  return 0;
}

#include "glfw_window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <fmt/format.h>

namespace clothsim {
namespace {
std::string last_glfw_error;
void on_glfw_error(int code, const char* message) { last_glfw_error = fmt::format("{} (GLFW error {:#x})", message, code); }
}  // namespace

std::unique_ptr<GlfwWindow> GlfwWindow::create(const std::string& title, int width, int height, bool vsync,
                                               std::string* why_not) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    if (why_not) *why_not = "cannot open a window: " + last_glfw_error;
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // HiDPI: window size in screen units
#ifndef NDEBUG
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
  GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w) {
    if (why_not) *why_not = "cannot create an OpenGL 4.3 core window: " + last_glfw_error;
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(w);
  if (!gl::load_gl_functions(reinterpret_cast<gl::GlProcLoader>(glfwGetProcAddress), why_not)) {
    glfwDestroyWindow(w);
    glfwTerminate();
    return nullptr;
  }
  glfwSwapInterval(vsync ? 1 : 0);
  return std::unique_ptr<GlfwWindow>(new GlfwWindow(w));
}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void GlfwWindow::make_current() { glfwMakeContextCurrent(window_); }

}  // namespace clothsim

// A GLFW window with an OpenGL 4.3 core context: the viewer's GlContext. Only the viewer
// links GLFW, so headless commands never need X11.
#pragma once

#include <memory>
#include <string>

#include "context.hpp"

struct GLFWwindow;

namespace clothsim {

class GlfwWindow final : public gl::GlContext {
 public:
  // nullptr (and why_not) when there is no display or no GL 4.3 driver.
  static std::unique_ptr<GlfwWindow> create(const std::string& title, int width, int height, bool vsync,
                                            std::string* why_not);
  ~GlfwWindow() override;
  void make_current() override;
  std::string description() const override { return "GLFW window"; }
  GLFWwindow* handle() const { return window_; }

 private:
  explicit GlfwWindow(GLFWwindow* w) : window_(w) {}
  GLFWwindow* window_;
};

}  // namespace clothsim

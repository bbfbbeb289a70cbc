#include "context.hpp"

#include <glad/gl.h>

#include <fmt/format.h>

#include <type_traits>

namespace clothsim::gl {

static_assert(std::is_same_v<GlProcLoader, GLADloadfunc>, "GlProcLoader must be glad's loader type");

GlContext::~GlContext() = default;

bool load_gl_functions(GlProcLoader loader, std::string* why_not) {
  const int version = gladLoadGL(loader);
  if (version == 0) {
    if (why_not) *why_not = "gladLoadGL could not load the OpenGL functions (no current context?)";
    return false;
  }
  const int major = GLAD_VERSION_MAJOR(version);
  const int minor = GLAD_VERSION_MINOR(version);
  if (major * 100 + minor < 403) {
    if (why_not) {
      *why_not = fmt::format("the driver offers OpenGL {}.{} ({}, \"{}\"); clothsim needs 4.3 for compute shaders",
                             major, minor, gl_renderer_string(), gl_version_string());
    }
    return false;
  }
  return true;
}

static std::string gl_string(GLenum name) {
  if (!glGetString) return "(GL not loaded)";
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "(unknown)";
}

std::string gl_renderer_string() { return gl_string(GL_RENDERER); }
std::string gl_version_string() { return gl_string(GL_VERSION); }

bool gl_renderer_is_llvmpipe() { return gl_renderer_string().find("llvmpipe") != std::string::npos; }

std::string software_renderer_notice() {
  if (!gl_renderer_is_llvmpipe()) return {};
  return "note: OpenGL runs on " + gl_renderer_string() +
         ", Mesa's software rasterizer on the CPU: fine for tests and small cloths, slow for large ones "
         "(README: Troubleshooting)";
}

}  // namespace clothsim::gl

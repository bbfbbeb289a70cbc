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

bool renderer_is_bit_exact(std::string_view renderer) { return renderer.starts_with("llvmpipe"); }

bool renderer_is_software(std::string_view renderer) {
  for (std::string_view software : {"llvmpipe", "softpipe", "lavapipe"})
    if (renderer.find(software) != std::string_view::npos) return true;
  return false;
}

bool gl_renderer_is_llvmpipe() { return renderer_is_bit_exact(gl_renderer_string()); }

std::string software_renderer_notice() {
  if (!renderer_is_software(gl_renderer_string())) return {};
  return "note: OpenGL runs on " + gl_renderer_string() +
         ", Mesa's software rasterizer on the CPU: fine for tests and small cloths, slow for large ones "
         "(README: Troubleshooting)";
}

}  // namespace clothsim::gl

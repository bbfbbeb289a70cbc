// Headless OpenGL through EGL: no window system, no display server, no GLFW.
#include <glad/gl.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>
#include <vector>

#include "context.hpp"

namespace clothsim::gl {
namespace {

const char* egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "unknown EGL error";
  }
}

std::string egl_failure(const char* call) {
  const EGLint error = eglGetError();
  return fmt::format("{} failed: {} (0x{:04x})", call, egl_error_name(error), error);
}

bool has_extension(const char* list, std::string_view name) {
  if (!list) return false;
  std::istringstream words(list);
  for (std::string word; words >> word;) {
    if (word == name) return true;
  }
  return false;
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context, EGLSurface surface, std::string description)
      : display_(display), context_(context), surface_(surface), description_(std::move(description)) {}

  // The display is left initialised: EGL displays are per-process singletons, and
  // terminating one would pull it from under any other context made on it.
  ~EglContext() override {
    if (eglGetCurrentContext() == context_) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(display_, context_);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
  }

  void make_current() override {
    if (!eglMakeCurrent(display_, surface_, surface_, context_)) {
      throw std::runtime_error(egl_failure("eglMakeCurrent"));
    }
  }

  void release() override {
    if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }

  std::string description() const override { return description_; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  EGLSurface surface_;
  std::string description_;
};

struct Candidate {
  std::string name;
  EGLDisplay display;
};

// The displays to try, best first (see create_headless_context).
std::vector<Candidate> candidate_displays(std::vector<std::string>& failures) {
  std::vector<Candidate> out;
  // Client extensions need EGL_EXT_client_extensions; without it this returns null.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client) eglGetError();
  auto get_platform_display = has_extension(client, "EGL_EXT_platform_base")
      ? reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"))
      : nullptr;

  if (get_platform_display && has_extension(client, "EGL_EXT_platform_device") &&
      has_extension(client, "EGL_EXT_device_enumeration")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices && query_string && query_devices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        // Mesa's software device is what the surfaceless platform gives anyway.
        if (has_extension(query_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software")) continue;
        EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY) {
          failures.push_back(fmt::format("EGL device {}: {}", i, egl_failure("eglGetPlatformDisplayEXT")));
        } else {
          out.push_back({fmt::format("EGL device {}", i), d});
        }
      }
    } else {
      failures.push_back(egl_failure("eglQueryDevicesEXT"));
    }
  }
  if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d == EGL_NO_DISPLAY) {
      failures.push_back("EGL surfaceless (Mesa): " + egl_failure("eglGetPlatformDisplayEXT"));
    } else {
      out.push_back({"EGL surfaceless (Mesa)", d});
    }
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d == EGL_NO_DISPLAY) {
    failures.push_back("EGL default display: " + egl_failure("eglGetDisplay"));
  } else {
    out.push_back({"EGL default display", d});
  }
  return out;
}

// When a 4.3 core context is refused, says which OpenGL the driver does offer.
std::string offered_gl_version(EGLDisplay display, EGLConfig config) {
  EGLContext probe = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (probe == EGL_NO_CONTEXT) return "";
  std::string version;
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, probe)) {
    using GetString = const GLubyte* (*)(GLenum);
    auto get_string = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
    const GLubyte* s = get_string ? get_string(GL_VERSION) : nullptr;
    if (s) version = fmt::format("; the driver offers OpenGL \"{}\"", reinterpret_cast<const char*>(s));
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(display, probe);
  return version;
}

std::unique_ptr<GlContext> try_display(const Candidate& candidate, const ContextOptions& options,
                                       std::string& why_not) {
  auto fail = [&why_not](std::string reason) -> std::unique_ptr<GlContext> {
    why_not = std::move(reason);
    return nullptr;
  };
  EGLDisplay display = candidate.display;
  EGLint egl_major = 0, egl_minor = 0;
  if (!eglInitialize(display, &egl_major, &egl_minor)) return fail(egl_failure("eglInitialize"));
  if (!eglBindAPI(EGL_OPENGL_API)) return fail(egl_failure("eglBindAPI(EGL_OPENGL_API)"));

  // Compute needs no surface at all; only a display without surfaceless contexts gets a pbuffer.
  const bool surfaceless = has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                      EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &config_count)) {
    return fail(egl_failure("eglChooseConfig"));
  }
  if (config_count == 0) return fail("eglChooseConfig found no config for desktop OpenGL");

  const EGLint context_attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION, 4,
      EGL_CONTEXT_MINOR_VERSION, 3,
      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
      EGL_CONTEXT_FLAGS_KHR, options.debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
      EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) {
    std::string reason = egl_failure("eglCreateContext (OpenGL 4.3 core)");
    return fail(reason + offered_gl_version(display, config));
  }
  EGLSurface surface = EGL_NO_SURFACE;
  if (!surfaceless) {
    const EGLint pbuffer_attributes[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
    surface = eglCreatePbufferSurface(display, config, pbuffer_attributes);
    if (surface == EGL_NO_SURFACE) {
      std::string reason = "no EGL_KHR_surfaceless_context and " + egl_failure("eglCreatePbufferSurface");
      eglDestroyContext(display, context);
      return fail(reason);
    }
  }
  auto result = std::make_unique<EglContext>(
      display, context, surface, fmt::format("{}, EGL {}.{}", candidate.name, egl_major, egl_minor));
  if (!eglMakeCurrent(display, surface, surface, context)) {
    return fail(egl_failure("eglMakeCurrent"));
  }
  if (!load_gl_functions(eglGetProcAddress, &why_not)) return nullptr;
  return result;
}

}  // namespace

std::unique_ptr<GlContext> create_headless_context(std::string* why_not, const ContextOptions& options) {
  std::vector<std::string> failures;
  for (const Candidate& candidate : candidate_displays(failures)) {
    std::string reason;
    if (auto context = try_display(candidate, options, reason)) return context;
    failures.push_back(candidate.name + ": " + reason);
  }
  if (why_not) {
    *why_not = "no OpenGL 4.3 core context through EGL";
    for (const std::string& failure : failures) *why_not += "\n  " + failure;
  }
  return nullptr;
}

}  // namespace clothsim::gl

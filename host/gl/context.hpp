// An OpenGL 4.3 core context, however it was made: EGL without a display for headless runs
// and tests (here), or a GLFW window for the viewer. Creating one also loads the GL
// functions (glad), so after a successful create the gl* calls work on this thread.
#pragma once

#include <memory>
#include <string>
#include <string_view>

namespace clothsim::gl {

class GlContext {
 public:
  virtual ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread.
  virtual void make_current() = 0;
  // Leaves the calling thread with no current context, so another thread may make this one
  // current (a context is current on at most one thread): the Python module does this after
  // every call, since Python may call it from any thread.
  virtual void release() {}
  // How the context was made, for messages: "EGL surfaceless (Mesa)", "EGL device 0", ...
  virtual std::string description() const = 0;

 protected:
  GlContext() = default;
};

struct ContextOptions {
  bool debug = false;  // ask for a debug context, so KHR_debug reports everything
};

// A context with no window and no display server, through EGL: an EGL device with a
// hardware driver first (so a GPU machine never silently runs on llvmpipe), then Mesa's
// surfaceless platform (llvmpipe when there is no GPU), then the default display.
// On failure returns nullptr and, if why_not is given, says what failed and why.
std::unique_ptr<GlContext> create_headless_context(std::string* why_not,
                                                   const ContextOptions& options = {});

// A GL function lookup, e.g. eglGetProcAddress or glfwGetProcAddress.
using GlProcLoader = void (*(*)(const char* name))();

// Loads the GL functions for the current context and checks it is OpenGL 4.3 or newer.
// Every context implementation calls this once after making itself current.
bool load_gl_functions(GlProcLoader loader, std::string* why_not);

// Facts about the current context, for logs and for tests that expect llvmpipe's exactness.
std::string gl_renderer_string();  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
std::string gl_version_string();   // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"

// Whether a renderer rounds exactly like the CPU reference, so that GPU results must equal it
// bit for bit: plain llvmpipe only, the renderer string starting with "llvmpipe". Zink on
// lavapipe says "zink (llvmpipe (LLVM ...))": the same LLVM back end, but the shaders reach it
// through SPIR-V and lavapipe's compiler, not the path the reference was made to match, so it
// runs in tolerance mode like a GPU (docs/testing.md, "The zink lane").
bool renderer_is_bit_exact(std::string_view renderer);
// Whether a renderer is one of Mesa's rasterizers on the CPU (llvmpipe, softpipe, lavapipe, zink
// on either): slow for large cloths, and its timestamps are not a GPU's.
bool renderer_is_software(std::string_view renderer);
// renderer_is_bit_exact of the current context: the tests' and `validate`'s exact mode.
bool gl_renderer_is_llvmpipe();
// One line for stderr when the context is a software rasterizer (llvmpipe, or zink on
// lavapipe), so a slow run says why; empty on a GPU.
std::string software_renderer_notice();

}  // namespace clothsim::gl

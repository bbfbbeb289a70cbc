#include "debug_output.hpp"

#include <glad/gl.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <mutex>

#include "objects.hpp"

namespace clothsim::gl {
namespace {

// The callback may run on any thread that has the context current, so the list is locked.
std::mutex g_mutex;
std::vector<std::string> g_errors;
std::vector<GLenum> g_codes;  // drained from glGetError, not yet reported by gl_errors_since_last_check
std::vector<GLenum> g_unraised;  // drained from glGetError, not yet thrown by check_gl_errors
size_t g_errors_raised = 0;  // g_errors[0 .. this) were named by a check_gl_errors already
DebugMode g_mode = DebugMode::Off;
#ifdef NDEBUG
constexpr bool kPrintErrors = false;
#else
constexpr bool kPrintErrors = true;  // debug builds show errors as they happen
#endif

const char* source_name(GLenum source) {
  switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
  }
}

const char* type_name(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    default: return "other";
  }
}

// Reads glGetError until it is clear, into both lists; returns the codes read now.
std::vector<GLenum> drain() {
  std::vector<GLenum> now;
  if (!glGetError) return now;
  // Bounded: a lost context may report GL_CONTEXT_LOST on every call.
  for (int i = 0; i < 16; ++i) {
    const GLenum code = glGetError();
    if (code == GL_NO_ERROR) break;
    now.push_back(code);
  }
  std::lock_guard lock(g_mutex);
  g_codes.insert(g_codes.end(), now.begin(), now.end());
  g_unraised.insert(g_unraised.end(), now.begin(), now.end());
  return now;
}

}  // namespace

const char* gl_error_name(unsigned code) {
  switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "unknown GL error";
  }
}

namespace {

void GLAD_API_PTR on_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                   const GLchar* message, const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  const std::string text(message, length >= 0 ? std::size_t(length) : std::char_traits<char>::length(message));
  // Compile errors reach the caller as ShaderError with file:line, so they are not counted twice.
  const bool error = source != GL_DEBUG_SOURCE_SHADER_COMPILER &&
                     (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH);
  const std::string line = fmt::format("GL {} ({}, id {}): {}", type_name(type), source_name(source), id, text);
  std::lock_guard lock(g_mutex);
  if (error) g_errors.push_back(line);
  if (g_mode == DebugMode::Verbose || (error && kPrintErrors)) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace

void enable_debug_output(DebugMode mode) {
  {
    std::lock_guard lock(g_mutex);
    g_mode = mode;
  }
  if (mode == DebugMode::Off) {
    glDisable(GL_DEBUG_OUTPUT);
    return;
  }
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

std::vector<std::string> gl_errors_since_last_check() {
  std::vector<std::string> errors;
  {
    std::lock_guard lock(g_mutex);
    errors.swap(g_errors);
    g_errors_raised = 0;
  }
  // An error KHR_debug already reported also sets the glGetError flag: report the flag
  // only when the callback saw nothing (debug output off or unsupported).
  poll_out_of_memory();
  std::vector<GLenum> codes;
  {
    std::lock_guard lock(g_mutex);
    codes.swap(g_codes);
  }
  if (errors.empty())
    for (GLenum code : codes) errors.push_back(fmt::format("glGetError: {} (0x{:04x})", gl_error_name(code), code));
  {
    // Reported here, so no later check_gl_errors throws for them (a test has looked).
    std::lock_guard lock(g_mutex);
    g_unraised.clear();
  }
  return errors;
}

bool poll_out_of_memory() {
  const std::vector<GLenum> now = drain();
  const bool out_of_memory = std::find(now.begin(), now.end(), GLenum(GL_OUT_OF_MEMORY)) != now.end();
  if (out_of_memory) {
    // The caller throws OutOfMemoryError for it: check_gl_errors does not raise it again.
    std::lock_guard lock(g_mutex);
    std::erase(g_unraised, GLenum(GL_OUT_OF_MEMORY));
  }
  return out_of_memory;
}

bool gl_errors_pending() {
  drain();
  std::lock_guard lock(g_mutex);
  return !g_unraised.empty();
}

void check_gl_errors(const std::string& where) {
  drain();
  std::vector<GLenum> codes;
  std::string driver_said;
  {
    std::lock_guard lock(g_mutex);
    codes.swap(g_unraised);
    // KHR_debug's own words for the first failing call since the last check (debug builds,
    // tests), left for the collector too.
    if (!codes.empty() && g_errors_raised < g_errors.size()) {
      driver_said = g_errors[g_errors_raised];
      if (const size_t more = g_errors.size() - g_errors_raised - 1; more > 0)
        driver_said += fmt::format(" (and {} more)", more);
    }
    if (!codes.empty()) g_errors_raised = g_errors.size();
  }
  if (codes.empty()) return;
  std::string names;
  for (GLenum code : codes) {
    const std::string name = fmt::format("{} (0x{:04x})", gl_error_name(code), code);
    if (names.find(name) == std::string::npos) names += (names.empty() ? "" : ", ") + name;
  }
  std::string message = fmt::format("{} {}", names, where);
  if (!driver_said.empty()) message += fmt::format("; the driver said: {}", driver_said);
  const bool out_of_memory = std::find(codes.begin(), codes.end(), GLenum(GL_OUT_OF_MEMORY)) != codes.end();
  if (out_of_memory) throw OutOfMemoryError(message);
  throw GlError(message, std::vector<unsigned>(codes.begin(), codes.end()));
}

}  // namespace clothsim::gl

// KHR_debug: the driver reports GL errors as they happen, with a message, instead of a
// glGetError code found later. Errors are collected so tests can assert there were none.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::gl {

enum class DebugMode {
  Off,     // no callback; gl_errors_since_last_check() still drains glGetError
  Errors,  // collect errors and high-severity messages (printed too in debug builds)
  Verbose, // as Errors, and print every other message except notifications to stderr
};

// Installs the debug callback on the current context, synchronous so that a message is
// reported inside the GL call that caused it (a debugger breakpoint shows the culprit).
void enable_debug_output(DebugMode mode);

// The errors collected since the last call, oldest first, and forgets them. Also drains
// glGetError, so errors are seen even where KHR_debug reports nothing.
std::vector<std::string> gl_errors_since_last_check();

// Drains glGetError (a cheap call: it does not wait for the GPU) and says whether it held
// GL_OUT_OF_MEMORY; a true answer is the caller's to report (it throws OutOfMemoryError).
// Every code drained, that one included, is still reported by the next
// gl_errors_since_last_check(), and every other code by the next check_gl_errors().
// Called after each buffer allocation and by the divergence guard's per-frame read-back.
bool poll_out_of_memory();

// A GL error found by check_gl_errors: what() names the code(s), e.g. "GL_INVALID_ENUM
// (0x0500)", and where it was found. (GL_OUT_OF_MEMORY is OutOfMemoryError, objects.hpp.)
struct GlError : std::runtime_error {
  GlError(const std::string& message, std::vector<unsigned> error_codes)
      : std::runtime_error(message), codes(std::move(error_codes)) {}
  std::vector<unsigned> codes;  // the GLenum values, oldest first
};

// Drains glGetError (no GPU wait, no sync: it reads the context's error flags) and throws when
// an error was raised since the previous check_gl_errors: OutOfMemoryError for
// GL_OUT_OF_MEMORY, GlError for any other code. The message is "<code names> <where>", followed
// by what KHR_debug said about the failing call when it is on (debug builds, tests). The codes
// stay for gl_errors_since_last_check(), so a test's CHECK_NO_GL_ERRORS still sees them.
// The GPU simulator calls it once before and once after each frame's passes.
void check_gl_errors(const std::string& where);
// Drains glGetError; true when check_gl_errors would throw (a code not yet raised is pending).
bool gl_errors_pending();
// check_gl_errors(where()), with the message built only when there is an error to report.
template <class Where> void check_gl_errors_lazily(Where&& where) {
  if (gl_errors_pending()) check_gl_errors(where());
}

// "GL_INVALID_ENUM", "GL_INVALID_OPERATION", ...; "unknown GL error" for anything else.
const char* gl_error_name(unsigned code);

}  // namespace clothsim::gl

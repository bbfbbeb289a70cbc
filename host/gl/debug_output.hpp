// KHR_debug: the driver reports GL errors as they happen, with a message, instead of a
// glGetError code found later. Errors are collected so tests can assert there were none.
#pragma once

#include <string>
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
// GL_OUT_OF_MEMORY. Every code drained, that one included, is still reported by the next
// gl_errors_since_last_check(). Called after each buffer allocation and once per frame.
bool poll_out_of_memory();

}  // namespace clothsim::gl

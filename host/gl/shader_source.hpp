// GLSL source assembly, no GL needed: `#include "file"` inlined (GLSL has no include),
// `#version 430 core` and the caller's #defines put first, and `#line N K` directives so
// the driver's error lines can be mapped back to the file they came from.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::gl {

// A shader that failed to load, preprocess, compile or link; what() is ready to print,
// with `path/to/file.comp:LINE: message` lines.
class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// #define NAME VALUE lines, in order, before any file text.
using Defines = std::vector<std::pair<std::string, std::string>>;

struct ShaderSource {
  std::string text;                 // the whole source, one string for glShaderSource
  std::vector<std::string> files;   // source-string number K of `#line N K` -> path ([0] = the preamble)
};

// Reads `path` and inlines its `#include "relative/path"` lines recursively, each relative
// to the file that includes it. Include guards in the files work as usual; an include
// cycle, a missing file or a stray `#version` is a ShaderError naming the chain of files.
// `#include <...>` lines (C++ headers in the shared layout header) are blanked: GLSL skips
// them only inside `#ifdef __cplusplus`, and no GLSL compiler needs them.
ShaderSource preprocess_shader(const std::filesystem::path& path, const Defines& defines);

// Rewrites the source-string:line prefixes of a driver's info log to file:line, for the
// formats of Mesa (`0:12(5): error: ...`), NVIDIA (`0(12) : error C0000: ...`) and
// AMD/glslang (`ERROR: 0:12: ...`). Lines it does not recognise are kept as they are.
std::string map_info_log(const std::string& log, const std::vector<std::string>& files);

}  // namespace clothsim::gl

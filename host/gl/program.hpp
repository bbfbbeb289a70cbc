// A linked GL program built from GLSL files: includes resolved, #defines injected, and
// compile errors reported as `file:line: message` (see shader_source.hpp).
#pragma once

#include <glad/gl.h>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>

#include "objects.hpp"
#include "shader_source.hpp"

namespace clothsim::gl {

class Program {
 public:
  // Both throw ShaderError on a missing file, a preprocessing error, or a compile or link
  // failure (the driver's log with its lines mapped back to the files).
  static Program compute(const std::filesystem::path& path, const Defines& defines = {});
  static Program graphics(const std::filesystem::path& vertex_path, const std::filesystem::path& fragment_path,
                          const Defines& defines = {});
  Program() = default;  // no GL program yet: only to be assigned one of the above

  void use() const;

  // Uniforms, set without binding the program (glProgramUniform*). A uniform the compiler
  // removed because it is unused is skipped, as GL does; a name that appears in none of the
  // sources is a ShaderError, so a typo does not pass silently.
  void set(std::string_view name, float value);
  void set(std::string_view name, int value);
  void set(std::string_view name, unsigned value);
  void set(std::string_view name, const glm::vec2& value);
  void set(std::string_view name, const glm::ivec2& value);
  void set(std::string_view name, const glm::ivec4& value);
  void set(std::string_view name, const glm::vec3& value);
  void set(std::string_view name, const glm::vec4& value);
  void set(std::string_view name, const glm::mat4& value);
  bool has_uniform(std::string_view name);
  // For a uniform set before every dispatch: look the location up once (same checks as
  // set(name, ...)), then set it by location with no string lookup.
  GLint location(std::string_view name);
  void set(GLint location, int value) { glProgramUniform1i(program_.get(), location, value); }
  void set(GLint location, unsigned value) { glProgramUniform1ui(program_.get(), location, value); }
  void set(GLint location, const glm::ivec4* values, GLsizei count) {
    glProgramUniform4iv(program_.get(), location, count, &values->x);
  }

  // Binds the program and dispatches; memory barriers remain the caller's (say who reads next).
  void dispatch(GLuint groups_x, GLuint groups_y = 1, GLuint groups_z = 1) const;
  // The same, the workgroups read on the GPU from the GL_DISPATCH_INDIRECT_BUFFER bound, at
  // `offset` bytes (three uints): a count a previous pass wrote, with no read-back.
  void dispatch_indirect(GLintptr offset) const;

  const std::string& name() const { return name_; }  // the file name(s), for messages
  // The GL name, only for introspection (e.g. the layout test's glGetProgramResource*).
  GLuint id() const { return program_.get(); }

 private:
  static void delete_program(GLuint id);
  Program(GLuint id, std::string name, std::string sources);

  detail::Name<delete_program> program_;
  std::string name_;
  std::string sources_;  // the preprocessed text, to tell a removed uniform from a typo
  std::unordered_map<std::string, GLint> locations_;
};

// Workgroups needed to cover `items` invocations, e.g. particles with WORKGROUP_SIZE each.
inline GLuint workgroups_for(std::size_t items, GLuint workgroup_size) {
  return GLuint((items + workgroup_size - 1) / workgroup_size);
}

}  // namespace clothsim::gl

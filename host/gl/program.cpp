#include "program.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <regex>
#include <vector>

namespace clothsim::gl {
namespace {

std::string info_log(GLuint object, bool is_program) {
  GLint length = 0;
  is_program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length) : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(std::max(length, 1)), '\0');
  GLsizei written = 0;
  is_program ? glGetProgramInfoLog(object, GLsizei(log.size()), &written, log.data())
             : glGetShaderInfoLog(object, GLsizei(log.size()), &written, log.data());
  log.resize(std::size_t(written));
  return log;
}

const char* stage_name(GLenum stage) {
  switch (stage) {
    case GL_COMPUTE_SHADER: return "compute";
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    default: return "shader";
  }
}

// A compiled shader stage; deleted once linked into the program.
struct Stage {
  GLuint id = 0;
  std::string text;
  Stage() = default;
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;
  ~Stage() {
    if (id) glDeleteShader(id);
  }
};

void compile(Stage& stage, GLenum type, const std::filesystem::path& path, const Defines& defines) {
  const ShaderSource source = preprocess_shader(path, defines);
  stage.text = source.text;
  stage.id = glCreateShader(type);
  const char* text = source.text.c_str();
  glShaderSource(stage.id, 1, &text, nullptr);
  glCompileShader(stage.id);
  GLint ok = GL_FALSE;
  glGetShaderiv(stage.id, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    throw ShaderError(fmt::format("{}: the {} shader does not compile:\n{}", path.string(), stage_name(type),
                                  map_info_log(info_log(stage.id, false), source.files)));
  }
}

GLuint link(const std::vector<const Stage*>& stages, const std::string& name) {
  const GLuint program = glCreateProgram();
  for (const Stage* stage : stages) glAttachShader(program, stage->id);
  glLinkProgram(program);
  for (const Stage* stage : stages) glDetachShader(program, stage->id);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(program, true);
    glDeleteProgram(program);
    throw ShaderError(fmt::format("{}: the program does not link:\n{}", name, log));
  }
  glObjectLabel(GL_PROGRAM, program, GLsizei(name.size()), name.c_str());
  return program;
}

}  // namespace

void Program::delete_program(GLuint id) { glDeleteProgram(id); }

Program::Program(GLuint id, std::string name, std::string sources)
    : program_(id), name_(std::move(name)), sources_(std::move(sources)) {}

Program Program::compute(const std::filesystem::path& path, const Defines& defines) {
  Stage stage;
  compile(stage, GL_COMPUTE_SHADER, path, defines);
  const std::string name = path.filename().string();
  return Program(link({&stage}, name), name, stage.text);
}

Program Program::graphics(const std::filesystem::path& vertex_path, const std::filesystem::path& fragment_path,
                          const Defines& defines) {
  Stage vertex, fragment;
  compile(vertex, GL_VERTEX_SHADER, vertex_path, defines);
  compile(fragment, GL_FRAGMENT_SHADER, fragment_path, defines);
  const std::string name = vertex_path.filename().string() + " + " + fragment_path.filename().string();
  return Program(link({&vertex, &fragment}, name), name, vertex.text + fragment.text);
}

void Program::use() const { glUseProgram(program_.get()); }

GLint Program::location(std::string_view name) {
  const std::string key(name);
  if (auto it = locations_.find(key); it != locations_.end()) return it->second;
  const GLint location = glGetUniformLocation(program_.get(), key.c_str());
  if (location < 0) {
    // Array and struct members ("a[2]", "s.x") are looked up by their leading identifier.
    const std::string base = key.substr(0, key.find_first_of("[."));
    const std::regex word("\\b" + base + "\\b");
    if (!std::regex_search(sources_, word)) {
      throw ShaderError(fmt::format("{}: no uniform named '{}' in the shader sources", name_, key));
    }
  }
  locations_.emplace(key, location);
  return location;
}

bool Program::has_uniform(std::string_view name) {
  return glGetUniformLocation(program_.get(), std::string(name).c_str()) >= 0;
}

void Program::set(std::string_view name, float value) { glProgramUniform1f(program_.get(), location(name), value); }
void Program::set(std::string_view name, int value) { glProgramUniform1i(program_.get(), location(name), value); }
void Program::set(std::string_view name, unsigned value) {
  glProgramUniform1ui(program_.get(), location(name), value);
}
void Program::set(std::string_view name, const glm::vec2& value) {
  glProgramUniform2fv(program_.get(), location(name), 1, glm::value_ptr(value));
}
void Program::set(std::string_view name, const glm::ivec2& value) {
  glProgramUniform2iv(program_.get(), location(name), 1, glm::value_ptr(value));
}
void Program::set(std::string_view name, const glm::ivec4& value) {
  glProgramUniform4iv(program_.get(), location(name), 1, glm::value_ptr(value));
}
void Program::set(std::string_view name, const glm::vec3& value) {
  glProgramUniform3fv(program_.get(), location(name), 1, glm::value_ptr(value));
}
void Program::set(std::string_view name, const glm::vec4& value) {
  glProgramUniform4fv(program_.get(), location(name), 1, glm::value_ptr(value));
}
void Program::set(std::string_view name, const glm::mat4& value) {
  glProgramUniformMatrix4fv(program_.get(), location(name), 1, GL_FALSE, glm::value_ptr(value));
}

void Program::dispatch(GLuint groups_x, GLuint groups_y, GLuint groups_z) const {
  use();
  glDispatchCompute(groups_x, groups_y, groups_z);
}

void Program::dispatch_indirect(GLintptr offset) const {
  use();
  glDispatchComputeIndirect(offset);
}

}  // namespace clothsim::gl

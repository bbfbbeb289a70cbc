// The GL plumbing every GPU pass stands on: context, shader loading, buffers, error reporting.
#include <glad/gl.h>

#include <numeric>
#include <vector>

#include "context.hpp"
#include "debug_output.hpp"
#include "gl_test_support.hpp"
#include "objects.hpp"
#include "program.hpp"

using namespace clothsim;
using clothsim::test::source_path;

namespace {

// The message of the ShaderError that `load` throws, or "" if it throws none.
template <class F> std::string shader_error_of(F&& load) {
  try {
    load();
  } catch (const gl::ShaderError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a headless context offers OpenGL 4.3 core or newer", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  INFO(test::gl_test_context().context->description() << ": " << gl::gl_renderer_string() << ", "
                                                       << gl::gl_version_string());
  CHECK(major * 100 + minor >= 403);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  CHECK((profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0);
  CHECK(!gl::gl_renderer_string().empty());
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a compute shader including the shared layout header compiles with the #defines first", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  gl::Program program = gl::Program::compute(source_path("tests/shaders/uses_layout.comp"), {{"WORKGROUP_SIZE", "64"}});
  GLint size[3] = {};
  glGetProgramiv(program.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
  CHECK(size[0] == 64);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a syntax error in an included file is reported at that file's line", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const std::string message =
      shader_error_of([] { gl::Program::compute(source_path("tests/shaders/syntax_error_main.comp")); });
  INFO(message);
  CHECK_THAT(message, Catch::Contains("syntax_error_included.glsl:5:"));
  CHECK_THAT(message, !Catch::Contains("0:"));
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("an error after (skipped) includes is reported at the including file's line", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const std::string message =
      shader_error_of([] { gl::Program::compute(source_path("tests/shaders/error_after_include.comp")); });
  INFO(message);
  CHECK_THAT(message, Catch::Contains("error_after_include.comp:10:"));
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a graphics program links and takes its uniforms and a misspelt uniform is an error", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  gl::Program program = gl::Program::graphics(source_path("tests/shaders/flat_colour.vert"),
                                              source_path("tests/shaders/flat_colour.frag"));
  CHECK(program.has_uniform("colour"));
  program.set("colour", glm::vec4(1, 0, 0, 1));
  CHECK_THROWS_AS(program.set("color", glm::vec4(1)), gl::ShaderError);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("an include cycle is an error naming the chain", "[shaders]") {
  const std::string message = shader_error_of(
      [] { gl::preprocess_shader(source_path("tests/shaders/cycle_main.comp"), {}); });
  INFO(message);
  CHECK_THAT(message, Catch::Contains("cycle_b.glsl:2: error: include cycle: "));
  CHECK_THAT(message, Catch::Contains("cycle_a.glsl -> ") && Catch::Contains("cycle_b.glsl -> "));
}

TEST_CASE("a missing include is an error naming the file and the including line", "[shaders]") {
  const std::string message = shader_error_of(
      [] { gl::preprocess_shader(source_path("tests/shaders/missing_include.comp"), {}); });
  INFO(message);
  CHECK_THAT(message, Catch::Contains("missing_include.comp:2: error: cannot open included file "));
  CHECK_THAT(message, Catch::EndsWith("no_such_file.glsl"));
}

TEST_CASE("preprocessing puts #version and the defines first and numbers files for #line", "[shaders]") {
  const gl::ShaderSource source =
      gl::preprocess_shader(source_path("tests/shaders/syntax_error_main.comp"), {{"A", "1"}, {"B", "2u"}});
  CHECK(source.text.rfind("#version 430 core\n#define A 1\n#define B 2u\n#line 1 1\n", 0) == 0);
  REQUIRE(source.files.size() == 3);
  CHECK_THAT(source.files[2], Catch::EndsWith("syntax_error_included.glsl"));
}

TEST_CASE("driver info logs are mapped to file:line in the Mesa / NVIDIA / glslang formats", "[shaders]") {
  const std::vector<std::string> files = {"<defines>", "a.comp", "dir/b.glsl"};
  CHECK(gl::map_info_log("2:12(5): error: syntax error\n", files) == "dir/b.glsl:12:5: error: syntax error\n");
  CHECK(gl::map_info_log("1(7) : error C0000: syntax error, unexpected ')'\n", files) ==
        "a.comp:7: error C0000: syntax error, unexpected ')'\n");
  CHECK(gl::map_info_log("ERROR: 2:3: 'x' : undeclared identifier\n", files) ==
        "dir/b.glsl:3: error: 'x' : undeclared identifier\n");
  CHECK(gl::map_info_log("9:1(1): error: x\nlinker says hi\n", files) == "<source string 9>:1:1: error: x\nlinker says hi\n");
}

TEST_CASE("a buffer gives back what was uploaded whole and in part", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  std::vector<float> values(1001);
  std::iota(values.begin(), values.end(), 0.5f);
  gl::Buffer buffer("round trip");
  gl::upload_vector(buffer, values);
  CHECK(buffer.size() == values.size() * sizeof(float));
  CHECK(gl::download_vector<float>(buffer) == values);

  const std::vector<float> patch = {-1.0f, -2.0f, -3.0f};
  buffer.upload(10 * sizeof(float), patch.size() * sizeof(float), patch.data());
  CHECK(gl::download_vector<float>(buffer, 9, 5) == std::vector<float>{9.5f, -1.0f, -2.0f, -3.0f, 13.5f});
  CHECK_THROWS_AS(buffer.upload(buffer.size() - 4, 8, patch.data()), std::out_of_range);

  gl::Buffer copy("copy");
  copy.allocate(buffer.size());
  copy.copy_from(buffer, 0, 0, buffer.size());
  buffer.clear_to_zero();
  CHECK(gl::download_vector<float>(copy, 10, 1) == std::vector<float>{-1.0f});
  CHECK(gl::download_vector<float>(buffer, 500, 1) == std::vector<float>{0.0f});

  gl::Buffer moved = std::move(copy);
  CHECK(moved.size() == buffer.size());
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a compute shader doubles the first n values of a buffer and leaves the rest", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const unsigned n = 1001;  // not a multiple of the workgroup size
  std::vector<float> values(n + 7);
  std::iota(values.begin(), values.end(), 1.0f);
  gl::Buffer buffer("values");
  gl::upload_vector(buffer, values);
  buffer.bind_base(GL_SHADER_STORAGE_BUFFER, 0);

  gl::Program program = gl::Program::compute(source_path("tests/shaders/double_values.comp"));
  program.set("count", n);
  program.dispatch(gl::workgroups_for(n, 64));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the read-back below reads the shader's writes

  const std::vector<float> result = gl::download_vector<float>(buffer);
  for (std::size_t i = 0; i < values.size(); ++i) {
    INFO("value " << i);
    REQUIRE(result[i] == (i < n ? 2.0f * values[i] : values[i]));
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a GL error is caught by the debug output collector exactly once", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  glBindBuffer(0xDEAD, 0);  // not a buffer target: GL_INVALID_ENUM
  const std::vector<std::string> errors = gl::gl_errors_since_last_check();
  REQUIRE(errors.size() == 1);
  CHECK_THAT(errors[0], Catch::Contains("error"));
  CHECK(gl::gl_errors_since_last_check().empty());
  CHECK_NO_GL_ERRORS();
}

// The shared layout header (compute/layout.glsl) against what GL actually made of it: the
// offsets, strides and block sizes a compiled shader reports through the program interface
// queries must be C++'s offsetof/sizeof, and values written through the C++ structs must be
// the values the shader reads. Fixture: tests/shaders/layout_probe.comp.
#include <glad/gl.h>

#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "gl_test_support.hpp"
#include "objects.hpp"
#include "program.hpp"
#include "../compute/layout.glsl"

using namespace clothsim;

namespace {

static_assert(std::is_standard_layout_v<layout::MaterialTexels> && std::is_standard_layout_v<layout::SphereCollider> &&
                  std::is_standard_layout_v<layout::PlaneCollider> && std::is_standard_layout_v<layout::StepParams> &&
                  std::is_standard_layout_v<layout::SubstepControl>,
              "offsetof needs standard-layout structs");

constexpr GLuint kBindingProbeUints = 21;  // BINDING_PROBE_UINTS in the fixture

gl::Program probe_program() {
  return gl::Program::compute(test::source_path("tests/shaders/layout_probe.comp"),
                              {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}});
}

template <class T> GLenum gl_type_of() {
  if constexpr (std::is_same_v<T, glm::vec4>) return GL_FLOAT_VEC4;
  if constexpr (std::is_same_v<T, glm::vec3>) return GL_FLOAT_VEC3;
  if constexpr (std::is_same_v<T, glm::uvec4>) return GL_UNSIGNED_INT_VEC4;
  if constexpr (std::is_same_v<T, float>) return GL_FLOAT;
  if constexpr (std::is_same_v<T, uint32_t>) return GL_UNSIGNED_INT;
  return GL_NONE;
}

// One struct member as C++ lays it out, under the name GL gives it.
struct Member {
  std::string name;  // e.g. "materials[0].keep" or "params.grid"
  GLint offset;      // offsetof in C++
  GLenum type;       // the GL type its C++ type stands for
};
#define MEMBER(Struct, prefix, member) \
  Member { prefix #member, GLint(offsetof(layout::Struct, member)), gl_type_of<decltype(layout::Struct::member)>() }

// One property of a named resource of `interface`; fails the test if the compiler dropped it.
GLint resource_property(const gl::Program& program, GLenum interface, const std::string& name, GLenum property) {
  const GLuint index = glGetProgramResourceIndex(program.id(), interface, name.c_str());
  INFO("resource " << name);
  REQUIRE(index != GL_INVALID_INDEX);
  GLint value = -1;
  glGetProgramResourceiv(program.id(), interface, index, 1, &property, 1, nullptr, &value);
  return value;
}

// Every member of an array-of-structs storage block: offset and type as C++, the array's
// stride and the block's minimum size (one element) both sizeof(the struct).
void check_storage_array(const gl::Program& program, const std::string& block, GLint binding, GLint stride,
                         const std::vector<Member>& members) {
  for (const Member& m : members) {
    INFO("buffer variable " << m.name);
    CHECK(resource_property(program, GL_BUFFER_VARIABLE, m.name, GL_OFFSET) == m.offset);
    CHECK(resource_property(program, GL_BUFFER_VARIABLE, m.name, GL_TOP_LEVEL_ARRAY_STRIDE) == stride);
    CHECK(resource_property(program, GL_BUFFER_VARIABLE, m.name, GL_TYPE) == GLint(m.type));
  }
  INFO("storage block " << block);
  CHECK(resource_property(program, GL_SHADER_STORAGE_BLOCK, block, GL_BUFFER_DATA_SIZE) == stride);
  CHECK(resource_property(program, GL_SHADER_STORAGE_BLOCK, block, GL_BUFFER_BINDING) == binding);
}

// Every member of a std140 uniform block: offset and type as C++, the block's size and binding.
void check_uniform_block(const gl::Program& program, const std::string& block, GLint binding, GLint size,
                         const std::vector<Member>& members) {
  for (const Member& m : members) {
    INFO("uniform " << m.name);
    CHECK(m.type != GLenum(GL_NONE));
    CHECK(resource_property(program, GL_UNIFORM, m.name, GL_OFFSET) == m.offset);
    CHECK(resource_property(program, GL_UNIFORM, m.name, GL_TYPE) == GLint(m.type));
  }
  INFO("uniform block " << block);
  CHECK(resource_property(program, GL_UNIFORM_BLOCK, block, GL_BUFFER_DATA_SIZE) == size);
  CHECK(resource_property(program, GL_UNIFORM_BLOCK, block, GL_BUFFER_BINDING) == binding);
}

template <class T> std::vector<T> two_of(const T& first, const T& second) { return {first, second}; }

}  // namespace

TEST_CASE("materials and colliders have the C++ offsets and strides in std430 storage buffers", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const gl::Program program = probe_program();
  check_storage_array(program, "Materials", BINDING_MATERIALS, sizeof(layout::MaterialTexels),
                      {MEMBER(MaterialTexels, "materials[0].", stiffness), MEMBER(MaterialTexels, "materials[0].", keep)});
  check_storage_array(program, "Spheres", BINDING_SPHERES, sizeof(layout::SphereCollider),
                      {MEMBER(SphereCollider, "spheres[0].", origin_radius), MEMBER(SphereCollider, "spheres[0].", keep),
                       MEMBER(SphereCollider, "spheres[0].", motion)});
  check_storage_array(program, "Planes", BINDING_PLANES, sizeof(layout::PlaneCollider),
                      {MEMBER(PlaneCollider, "planes[0].", point), MEMBER(PlaneCollider, "planes[0].", normal),
                       MEMBER(PlaneCollider, "planes[0].", motion)});
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("every step parameter has the C++ offset and type, and the block the C++ size, in std140", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const gl::Program program = probe_program();
  // The field list of layout.glsl itself, so a field added there is checked here too.
  std::vector<Member> members;
#define STEP_PARAMS_MEMBER(type, name) members.push_back(MEMBER(StepParams, "params.", name));
  STEP_PARAMS_FIELDS(STEP_PARAMS_MEMBER)
#undef STEP_PARAMS_MEMBER
  REQUIRE(members.size() >= 19);
  check_uniform_block(program, "StepParamsBlock", BINDING_STEP_PARAMS, GLint(sizeof(layout::StepParams)), members);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("every field of the substep's control has the C++ offset and type, and its block the C++ size, in std140",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const gl::Program program = probe_program();
  std::vector<Member> members;
#define SUBSTEP_CONTROL_MEMBER(type, name) members.push_back(MEMBER(SubstepControl, "control.", name));
  SUBSTEP_CONTROL_FIELDS(SUBSTEP_CONTROL_MEMBER)
#undef SUBSTEP_CONTROL_MEMBER
  REQUIRE(members.size() == 3);
  check_uniform_block(program, "SubstepControlBlock", BINDING_SUBSTEP_CONTROL, GLint(sizeof(layout::SubstepControl)),
                      members);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the texel views step through each struct by its std430 stride", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const gl::Program program = probe_program();
  // A view reads member m of element k as RGBA32F texel k * STRUCT_TEXELS + m (particle_views.glsl,
  // collide_objects.glsl): right only if the storage buffer's stride is STRUCT_TEXELS vec4s.
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "materials[0].stiffness", GL_TOP_LEVEL_ARRAY_STRIDE) == MATERIAL_TEXELS * 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "materials[0].keep", GL_OFFSET) == 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "spheres[0].origin_radius", GL_TOP_LEVEL_ARRAY_STRIDE) ==
        SPHERE_TEXELS * 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "spheres[0].keep", GL_OFFSET) == 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "planes[0].point", GL_TOP_LEVEL_ARRAY_STRIDE) ==
        PLANE_TEXELS * 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "planes[0].normal", GL_OFFSET) == 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "spheres[0].motion", GL_OFFSET) == 32);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "planes[0].motion", GL_OFFSET) == 32);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "meshes[0].row0", GL_TOP_LEVEL_ARRAY_STRIDE) == MESH_TEXELS * 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "meshes[0].dims", GL_OFFSET) == 64);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "meshes[0].material", GL_OFFSET) == 96);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a positions buffer is an array of vec4 with a 16-byte stride", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  const gl::Program program = probe_program();
  static_assert(sizeof(glm::vec4) == 16);
  // GL_ARRAY_STRIDE, not GL_TOP_LEVEL_ARRAY_STRIDE: the latter is only defined (non-zero) for
  // top-level arrays of structures or of arrays, like materials[] above.
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "pos[0]", GL_OFFSET) == 0);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "pos[0]", GL_ARRAY_STRIDE) == 16);
  CHECK(resource_property(program, GL_BUFFER_VARIABLE, "pos[0]", GL_TYPE) == GL_FLOAT_VEC4);
  CHECK(resource_property(program, GL_SHADER_STORAGE_BLOCK, "Positions", GL_BUFFER_DATA_SIZE) == 16);
  CHECK(resource_property(program, GL_SHADER_STORAGE_BLOCK, "Positions", GL_BUFFER_BINDING) == BINDING_POSITIONS);
  GLint size[3] = {};
  glGetProgramiv(program.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
  CHECK(size[0] == WORKGROUP_SIZE);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("values written through the C++ layout structs are the values the shader reads", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  gl::Program program = probe_program();
  // Distinct values everywhere, so a member read from its neighbour's place shows: field k
  // holds the bits 0x3f800000 + k (a float near 1) whatever its type.
  layout::StepParams params{};
  std::vector<uint32_t> want_uints;
  auto fill = [&](auto& field) {
    constexpr size_t words = sizeof(field) / 4;
    uint32_t bits[words];
    for (size_t w = 0; w < words; ++w) want_uints.push_back(bits[w] = 0x3f800000u + uint32_t(want_uints.size()));
    std::memcpy(&field, bits, sizeof(field));
  };
#define STEP_PARAMS_FILL(type, name) fill(params.name);
  STEP_PARAMS_FIELDS(STEP_PARAMS_FILL)
#undef STEP_PARAMS_FILL
  layout::SubstepControl control{};  // after the parameters, as the probe writes them
#define SUBSTEP_CONTROL_FILL(type, name) fill(control.name);
  SUBSTEP_CONTROL_FIELDS(SUBSTEP_CONTROL_FILL)
#undef SUBSTEP_CONTROL_FILL
  const auto materials = two_of<layout::MaterialTexels>({{-1, -2, -3, -4}, {-5, -6, -7, -8}}, {{1, 2, 3, 4}, {5, 6, 7, 8}});
  const auto spheres =
      two_of<layout::SphereCollider>({{-1, -1, -1, -1}, {-1, -1, -1, -1}, {-1, -1, -1, -1}},
                                     {{11, 12, 13, 14}, {15, 16, 17, 18}, {19, 20, 21, 22}});
  const auto planes =
      two_of<layout::PlaneCollider>({{-1, -1, -1, -1}, {-1, -1, -1, -1}, {-1, -1, -1, -1}},
                                    {{21, 22, 23, 24}, {25, 26, 27, 28}, {29, 30, 31, 32}});

  gl::Buffer params_buffer("probe params"), control_buffer("probe control"), materials_buffer("probe materials"), spheres_buffer("probe spheres"),
      planes_buffer("probe planes"), floats("probe floats"), uints("probe uints");
  params_buffer.allocate(sizeof(params), &params, GL_STATIC_DRAW);
  control_buffer.allocate(sizeof(control), &control, GL_STATIC_DRAW);
  gl::upload_vector(materials_buffer, materials);
  gl::upload_vector(spheres_buffer, spheres);
  gl::upload_vector(planes_buffer, planes);
  floats.allocate(8 * sizeof(glm::vec4));
  uints.allocate(want_uints.size() * sizeof(uint32_t));
  params_buffer.bind_base(GL_UNIFORM_BUFFER, BINDING_STEP_PARAMS);
  control_buffer.bind_base(GL_UNIFORM_BUFFER, BINDING_SUBSTEP_CONTROL);
  materials_buffer.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MATERIALS);
  spheres_buffer.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SPHERES);
  planes_buffer.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_PLANES);
  floats.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS);
  uints.bind_base(GL_SHADER_STORAGE_BUFFER, kBindingProbeUints);
  program.dispatch(1);
  // The read-backs below come next.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);

  const std::vector<glm::vec4> want_floats = {materials[1].stiffness,    materials[1].keep,     spheres[1].origin_radius,
                                              spheres[1].keep, planes[1].point, planes[1].normal,
                                              spheres[1].motion, planes[1].motion};
  const auto got_floats = gl::download_vector<glm::vec4>(floats);
  const auto got_uints = gl::download_vector<uint32_t>(uints);
  REQUIRE(got_floats.size() == want_floats.size());
  REQUIRE(got_uints.size() == want_uints.size());
  for (size_t k = 0; k < want_floats.size(); ++k) {
    INFO("float vec4 " << k);
    CHECK(std::memcmp(&got_floats[k], &want_floats[k], sizeof(glm::vec4)) == 0);
  }
  for (size_t k = 0; k < want_uints.size(); ++k) {
    INFO("step parameter (then substep control) word " << k);
    CHECK(got_uints[k] == want_uints[k]);
  }
  CHECK_NO_GL_ERRORS();
}

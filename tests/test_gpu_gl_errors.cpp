// GL errors in release builds too: GpuSimulator::step_frame reads glGetError (no GPU wait)
// before and after each frame's passes and throws gl::GlError naming the error and the frame
// (simulate maps it to exit 1 with the message; host/app/main.cpp). KHR_debug stays on for
// debug builds and tests, whose collector still sees every error.
#include <catch2/catch.hpp>

#include <set>

#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

std::filesystem::path compute_dir() { return test::source_path("compute"); }

// A small cloth on which every kind of pass runs: wind, self-collision, a sphere, a plane.
Scene busy_scene(const std::string& solver) {
  return test::make_scene(9, 7, 0, {"simulation.solver=\"" + solver + "\"", "simulation.simulation_steps=6"},
                          R"(, "wind": {"velocity": [1, 0, 2]},
                             "sphere": {"origin": [0.5, 0.7, 0.5], "radius": 0.2, "friction": 0.3},
                             "plane": {"point": [0, 0.4, 0], "normal": [0, 1, 0], "friction": 0.5})");
}

// The GL names that are programs, among the first `limit`.
std::set<GLuint> live_programs(GLuint limit = 4096) {
  std::set<GLuint> out;
  for (GLuint id = 1; id < limit; ++id)
    if (glIsProgram(id)) out.insert(id);
  return out;
}

}  // namespace

TEST_CASE("a run of frames with every pass raises no GL error and step_frame throws nothing", "[gpu][gl]") {
  REQUIRE_GL_CONTEXT();
  for (const char* solver : {"classic", "fabric"}) {
    INFO(solver);
    const Scene s = busy_scene(solver);
    const ClothModel m = build_cloth(s);
    GpuSimulator sim(s, m, compute_dir());
    for (int f = 0; f < 5; ++f) {
      CHECK_NOTHROW(sim.step_frame());
      CHECK_NOTHROW(sim.passes().divergence().take(false));
    }
    CHECK_FALSE(gl::gl_errors_pending());
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a GL error raised between frames stops the next step_frame with its name and the frame", "[gpu][gl]") {
  REQUIRE_GL_CONTEXT();
  const Scene s = busy_scene("classic");
  const ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, compute_dir());
  sim.step_frame();
  sim.step_frame();

  glBindBuffer(0xDEAD, 0);  // not a buffer target: GL_INVALID_ENUM
  try {
    sim.step_frame();
    FAIL("step_frame did not throw for a GL_INVALID_ENUM");
  } catch (const gl::GlError& e) {
    INFO(e.what());
    CHECK_THAT(e.what(), Catch::StartsWith("GL_INVALID_ENUM (0x0500) before frame 3 on the GPU"));
    CHECK_THAT(e.what(), Catch::Contains("outside the simulation"));
    CHECK(e.codes == std::vector<unsigned>{GL_INVALID_ENUM});
  }
  // The collector (KHR_debug, then glGetError) still reports it: exactly the one error.
  CHECK_THAT(test::take_gl_errors(), Catch::Contains("error"));
  // Raised once: the frame not run then runs now.
  CHECK_NOTHROW(sim.step_frame());
  CHECK(sim.passes().divergence().frame() == 3);

  glUseProgram(0xFFFFFFF0u);  // not a program name: GL_INVALID_VALUE
  CHECK_THROWS_WITH(sim.step_frame(), Catch::StartsWith("GL_INVALID_VALUE (0x0501) before frame 4"));
  test::take_gl_errors();

  // An error the divergence guard's read-back drained (it throws only for GL_OUT_OF_MEMORY) is
  // not lost: the next frame raises it.
  glBindBuffer(0xDEAD, 0);
  CHECK_NOTHROW(sim.passes().divergence().take(true));
  CHECK_THROWS_AS(sim.step_frame(), gl::GlError);
  test::take_gl_errors();
  CHECK_NOTHROW(sim.step_frame());
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a GL error raised by a frame's own passes stops that frame, naming it", "[gpu][gl]") {
  REQUIRE_GL_CONTEXT();
  const Scene s = test::make_scene(7, 5, 0, {"simulation.self_collision=false"});
  const ClothModel m = build_cloth(s);
  const std::set<GLuint> before = live_programs();
  {
    GpuSimulator sim(s, m, compute_dir());
    sim.step_frame();
    // Delete the simulator's programs behind its back: its passes then use names that are no
    // longer programs (GL_INVALID_VALUE from glUseProgram and glProgramUniform*).
    for (GLuint id : live_programs())
      if (!before.count(id)) glDeleteProgram(id);
    REQUIRE_FALSE(gl::gl_errors_pending());  // the deletes themselves are fine
    try {
      sim.step_frame();
      FAIL("step_frame did not throw");
    } catch (const gl::GlError& e) {
      INFO(e.what());
      CHECK_THAT(e.what(), Catch::StartsWith("GL_INVALID_VALUE (0x0501)"));
#ifdef NDEBUG
      // Release builds: the check after the passes, which lists them.
      CHECK_THAT(e.what(), Catch::Contains("in frame 2 on the GPU: raised by one of the frame's passes (30 substeps of "
                                           "advance, solve_length_constraints; then compute_normals"));
#else
      // Debug builds: the check after the first pass.
      CHECK_THAT(e.what(), Catch::Contains("after the pass") && Catch::Contains("(substep 1 of frame 2)"));
#endif
    }
  }  // the simulator's destructor deletes the names again: more errors, not checked here
  test::take_gl_errors();
  CHECK_NO_GL_ERRORS();
}

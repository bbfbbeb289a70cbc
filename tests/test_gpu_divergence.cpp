// The divergence guard on the GPU: the check_divergence reduction against its CPU twin, the
// kept last good frame, results at most one frame late, the same verdicts as the reference,
// 10,000-substep stress runs, and GL_OUT_OF_MEMORY reported instead of ignored.
#include <catch2/catch.hpp>

#include <limits>
#include <random>

#include "gl_test_support.hpp"
#include "gpu_memory.hpp"
#include "gpu_simulator.hpp"
#include "stress_cases.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

std::filesystem::path compute_dir() { return test::source_path("compute"); }

// llvmpipe keeps buffers in malloc'ed memory; under AddressSanitizer a failed huge malloc
// aborts the process (allocator_may_return_null=0) instead of reaching the driver as null.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

#define SKIP_UNDER_ADDRESS_SANITIZER()                                                             \
  do {                                                                                             \
    if (kAddressSanitizer) {                                                                       \
      WARN("skipped: AddressSanitizer aborts on the failed 64 TiB allocation this test provokes"); \
      return;                                                                                      \
    }                                                                                              \
  } while (false)

// Positions spread over a few metres, from a fixed seed.
std::vector<glm::vec4> random_positions(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-3.f, 3.f);
  std::vector<glm::vec4> p(n);
  for (auto& x : p) x = {u(rng), u(rng), u(rng), 1.f};
  return p;
}

// Min/max of -0 and +0 may pick either; everything else must be the same float.
bool same_bounds(const ClothBounds& a, const ClothBounds& b) { return a.finite == b.finite && a.lo == b.lo && a.hi == b.hi; }

GLint block_property(const gl::Program& program, const char* block, GLenum property) {
  const GLuint index = glGetProgramResourceIndex(program.id(), GL_SHADER_STORAGE_BLOCK, block);
  REQUIRE(index != GL_INVALID_INDEX);
  GLint value = -1;
  glGetProgramResourceiv(program.id(), GL_SHADER_STORAGE_BLOCK, index, 1, &property, 1, nullptr, &value);
  return value;
}

}  // namespace

TEST_CASE("the guard's buffers have the C++ sizes in std430", "[gpu][divergence]") {
  REQUIRE_GL_CONTEXT();
  const gl::Program check = gl::Program::compute(compute_dir() / "check_divergence.comp",
                                                 {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}});
  const gl::Program keep = gl::Program::compute(compute_dir() / "keep_last_good.comp",
                                                {{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}});
  CHECK(block_property(check, "Bounds", GL_BUFFER_DATA_SIZE) == GLint(sizeof(layout::FrameBounds)));
  CHECK(block_property(check, "Bounds", GL_BUFFER_BINDING) == BINDING_FRAME_BOUNDS);
  // The header, then one vec4 of the unsized array.
  CHECK(block_property(keep, "LastGood", GL_BUFFER_DATA_SIZE) == GLint(sizeof(layout::LastGoodHeader) + 16));
  CHECK(block_property(keep, "LastGood", GL_BUFFER_BINDING) == BINDING_LAST_GOOD);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("GPU check_divergence matches its CPU twin on 7x5, 33x17 and 45x29 cloths, with NaN and Inf",
          "[gpu][divergence]") {
  REQUIRE_GL_CONTEXT();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (auto [nw, nh] : {std::pair{7, 5}, {33, 17}, {45, 29}}) {
    const Scene s = test::make_scene(nw, nh, 0);
    const ClothModel m = build_cloth(s);
    GpuDivergenceGuard guard(s, m, compute_dir());
    gl::Buffer buffer("test positions");
    const int n = m.count();
    std::vector<std::vector<glm::vec4>> states;
    states.push_back(random_positions(n, 1));
    states.push_back(random_positions(n, 2));
    states.back()[n / 2].y = nan;
    states.push_back(random_positions(n, 3));
    states.back()[n - 1].z = -inf;  // in the last, partial workgroup
    states.push_back(std::vector<glm::vec4>(n, glm::vec4(inf, 0.f, 0.f, 1.f)));  // nothing finite: an empty box
    for (size_t k = 0; k < states.size(); ++k) {
      INFO(nw << "x" << nh << " state " << k);
      gl::upload_vector(buffer, states[k]);
      guard.check(buffer);
      const auto checks = guard.take(true);
      REQUIRE(checks.size() == 1);
      CHECK(checks[0].frame == int(k) + 1);
      const ClothBounds want = check_divergence(states[k]);
      CHECK(same_bounds(checks[0].bounds, want));
      CHECK(checks[0].bounds.finite == (k == 0));
    }
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the GPU keeps the frame before the first failure, and nothing after it until a reset",
          "[gpu][divergence]") {
  REQUIRE_GL_CONTEXT();
  const Scene s = test::make_scene(7, 5, 1, {"cloth.pinned=[[0,0],[6,0]]", "simulation.self_collision=false"});
  const ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, compute_dir());
  CpuBackend<float> cpu(s, m);
  for (int f = 1; f <= 3; ++f) {
    sim.step_frame();
    cpu.step_frame();
  }
  CHECK(sim.passes().divergence().take(true).size() == 2);  // frames 2 and 3: the first was dropped untaken
  // A NaN put into frame 4 makes it fail; the NaN stays in the cloth from then on.
  sim.hold_particle(m.index(3, 2), glm::vec3(std::numeric_limits<float>::quiet_NaN()));
  for (int f = 4; f <= 6; ++f) sim.step_frame();
  const auto checks = sim.passes().divergence().take(true);
  REQUIRE(checks.size() == 2);
  CHECK(checks[0].frame == 5);
  CHECK_FALSE(checks[1].bounds.finite);
  int frame = -1;
  const std::vector<glm::vec4> kept = sim.passes().divergence().last_good(&frame);
  CHECK(frame == 3);
  const ClothSnapshot reference = cpu.snapshot();
  const double tolerance = gl::gl_renderer_is_llvmpipe() ? 0.0 : 1e-5;  // llvmpipe matches bit for bit
  for (int i = 0; i < m.count(); ++i) CHECK(glm::length(glm::dvec3(kept[i]) - glm::dvec3(reference.pos[i])) <= tolerance);

  sim.reset();
  CHECK(sim.passes().divergence().last_good(&frame) == initial_state<float>(m).pos);
  CHECK(frame == 0);
  sim.step_frame();
  const auto after = sim.passes().divergence().take(true);
  REQUIRE(after.size() == 1);
  CHECK(after[0].frame == 1);
  CHECK(within_limits(after[0].bounds, divergence_limits(s, m)));
  sim.passes().divergence().last_good(&frame);
  CHECK(frame == 1);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("each GPU frame's check is handed over once, in order, at most one frame late", "[gpu][divergence]") {
  REQUIRE_GL_CONTEXT();
  const Scene s = test::make_scene(33, 17, 0, {"cloth.pinned=[[0,0],[32,0]]", "simulation.simulation_steps=3"});
  const ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, compute_dir());
  int taken = 0;
  for (int f = 1; f <= 20; ++f) {
    sim.step_frame();
    for (const FrameCheck& c : sim.passes().divergence().take(false)) CHECK(c.frame == ++taken);
    CHECK(taken >= f - 1);
  }
  for (const FrameCheck& c : sim.passes().divergence().take(true)) CHECK(c.frame == ++taken);
  CHECK(taken == 20);
  CHECK(sim.passes().divergence().take(true).empty());
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("allocating a buffer the driver cannot hold throws, naming the buffer and the size", "[gpu][divergence]") {
  REQUIRE_GL_CONTEXT();
  SKIP_UNDER_ADDRESS_SANITIZER();
  gl::Buffer huge("a test buffer far too large");
  const std::size_t bytes = std::size_t(1) << 46;  // 64 TiB
  try {
    huge.allocate(bytes);
    FAIL("no GL_OUT_OF_MEMORY for 64 TiB");
  } catch (const gl::OutOfMemoryError& e) {
    CHECK_THAT(e.what(), Catch::Contains("GL_OUT_OF_MEMORY"));
    CHECK_THAT(e.what(), Catch::Contains("'a test buffer far too large'"));
    CHECK_THAT(e.what(), Catch::Contains(std::to_string(bytes) + " bytes"));
  }
  CHECK(huge.size() == 0);
  test::take_gl_errors();  // the driver's own report of the same error
  // The buffer is still usable at a sane size.
  huge.allocate(64);
  CHECK(huge.size() == 64);
  CHECK_NO_GL_ERRORS();
}

namespace {
// Not through gl::Buffer, which would throw at once: a raw allocation that fails, as a
// driver's internal one might in the middle of a frame.
void fail_a_raw_allocation() {
  GLuint raw = 0;
  glGenBuffers(1, &raw);
  glBindBuffer(GL_COPY_WRITE_BUFFER, raw);
  glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(std::size_t(1) << 46), nullptr, GL_DYNAMIC_DRAW);
  glDeleteBuffers(1, &raw);
}
}  // namespace

TEST_CASE("a GL_OUT_OF_MEMORY during a run stops it at the next per-frame check", "[gpu][divergence]") {
  REQUIRE_GL_CONTEXT();
  SKIP_UNDER_ADDRESS_SANITIZER();
  const Scene s = test::make_scene(7, 5, 0, {"simulation.self_collision=false"});
  const ClothModel m = build_cloth(s);
  GpuSimulator sim(s, m, compute_dir());
  sim.step_frame();
  CHECK_NOTHROW(sim.passes().divergence().take(false));
  // Found by the next frame's check of glGetError (before its passes), as OutOfMemoryError
  // (exit 2, like any input too large for the GPU), naming the frame.
  fail_a_raw_allocation();
  CHECK_THROWS_AS(sim.step_frame(), gl::OutOfMemoryError);
  test::take_gl_errors();
  fail_a_raw_allocation();
  CHECK_THROWS_WITH(sim.step_frame(), Catch::Contains("GL_OUT_OF_MEMORY") && Catch::Contains("frame 2"));
  test::take_gl_errors();
  CHECK_NOTHROW(sim.step_frame());
  // Between a frame and its read-back: the divergence guard's take finds it, and reports it
  // once: the next frame does not throw for it again.
  fail_a_raw_allocation();
  CHECK_THROWS_WITH(sim.passes().divergence().take(false), Catch::Contains("GL_OUT_OF_MEMORY") && Catch::Contains("frame 2"));
  CHECK_NOTHROW(sim.step_frame());
  test::take_gl_errors();
  CHECK_NOTHROW(sim.passes().divergence().take(true));
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a cloth larger than the free memory the driver reports is refused before allocating", "[divergence]") {
  // Pure arithmetic: the drivers that report free memory (NVIDIA, AMD) are not llvmpipe.
  const Scene s = test::make_scene(512, 512, 0);
  const ClothModel m = build_cloth(s);
  const uint64_t needed = simulator_bytes(m);
  CHECK(needed > uint64_t(m.count()) * 100);
  CHECK_FALSE(memory_shortfall(s, m, needed, std::nullopt).has_value());
  CHECK_FALSE(memory_shortfall(s, m, needed, GpuMemoryInfo{needed, "GL_NVX_gpu_memory_info"}).has_value());
  const auto message = memory_shortfall(s, m, needed, GpuMemoryInfo{needed / 2, "GL_NVX_gpu_memory_info"});
  REQUIRE(message.has_value());
  CHECK_THAT(*message, Catch::StartsWith("<test>: cloth.num_width_points: a 512x512 grid needs about"));
  CHECK_THAT(*message, Catch::Contains("(GL_NVX_gpu_memory_info)"));
  CHECK_THAT(*message, Catch::Contains("--backend cpu"));
}

TEST_CASE("the free memory a driver reports is believed for GPUs, not for Mesa's software rasterizers", "[divergence]") {
  // Mesa 25.0.7's llvmpipe exposes GL_NVX_gpu_memory_info and answers 0 KiB (21 MiB in a
  // context with the simulator's buffers) on a machine with 24 GiB free: believed, it refused
  // a 256x256 cloth. Its memory is the machine's, so no check applies there.
  const std::string llvmpipe = "llvmpipe (LLVM 15.0.6, 256 bits)";
  CHECK_FALSE(memory_report(llvmpipe, 21 * 1024, std::nullopt).has_value());
  CHECK_FALSE(memory_report(llvmpipe, 0, 0).has_value());
  CHECK_FALSE(memory_report("softpipe", 1024, std::nullopt).has_value());
  CHECK_FALSE(memory_report("NVIDIA H200/PCIe/SSE2", std::nullopt, std::nullopt).has_value());
  // A report of 0 free is a driver that does not count: no check.
  CHECK_FALSE(memory_report("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 19.1.7, DRM 3.61)", 0, std::nullopt).has_value());
  const auto nvidia = memory_report("NVIDIA H200/PCIe/SSE2", 1000, std::nullopt);
  REQUIRE(nvidia.has_value());
  CHECK(nvidia->available_bytes == 1000u * 1024u);
  CHECK(nvidia->source == "GL_NVX_gpu_memory_info");
  const auto amd = memory_report("AMD Radeon (TM) Pro", std::nullopt, 2000);
  REQUIRE(amd.has_value());
  CHECK(amd->available_bytes == 2000u * 1024u);
  CHECK(amd->source == "GL_ATI_meminfo");
  // Both: NVX first, as before.
  CHECK(memory_report("AMD Radeon RX 7900 XTX (radeonsi)", 3000, 4000)->source == "GL_NVX_gpu_memory_info");
}

namespace {

// The case on the GPU and on the float reference. On llvmpipe the two agree bit for bit, so
// they must fail (or not) at the same frame with the same message and end in the same state.
void run_gpu_stress(const std::string& name) {
  const test::StressCase c = test::stress_case(name);
  const Scene s = test::stress_scene(c);
  const ClothModel m = build_cloth(s);
  GpuBackend gpu(nullptr, s, m, compute_dir());  // runs in the tests' shared context
  const test::StressOutcome out = test::run_stress(gpu, s, m, c);
  test::check_stress_outcome(c, out);
  CpuBackend<float> cpu(s, m);
  const test::StressOutcome want = test::run_stress(cpu, s, m, c);
  if (gl::gl_renderer_is_llvmpipe()) {
    CHECK(out.message == want.message);
    CHECK(out.good_frame == want.good_frame);
    CHECK(test::max_abs_diff(out.good.pos, want.good.pos) == 0);
    if (!c.diverges) CHECK(test::max_abs_diff(out.last.pos, want.last.pos) == 0);
  }
  if (name == "everything pinned") {
    const State<float> initial = initial_state<float>(m);
    for (int i = 0; i < m.count(); ++i) CHECK(glm::dvec4(initial.pos[i]) == out.last.pos[i]);
  }
}

}  // namespace

#define GPU_STRESS_TEST(NAME)                                                     \
  TEST_CASE("10,000 substeps on the GPU: " NAME, "[gpu][divergence][stress][long]") { \
    REQUIRE_GL_CONTEXT();                                                         \
    run_gpu_stress(NAME);                                                         \
    CHECK_NO_GL_ERRORS();                                                         \
  }

GPU_STRESS_TEST("stiff with enough substeps")
GPU_STRESS_TEST("far too stiff for its substeps")
GPU_STRESS_TEST("frictionless colliders")
GPU_STRESS_TEST("colliders with full friction")
GPU_STRESS_TEST("zero gravity, no damping")
GPU_STRESS_TEST("everything pinned")
GPU_STRESS_TEST("nothing pinned, self-collision on a plane")
GPU_STRESS_TEST("starting inside a sphere")
GPU_STRESS_TEST("a plane through the cloth")

// The renderer-string rule (host/gl/context.cpp): which renderers must match the CPU reference
// bit for bit (plain llvmpipe) and which run in tolerance mode (zink on lavapipe, GPUs). No
// context needed: a CPU-tier test of the GPU binary.
#include <catch2/catch.hpp>

#include "context.hpp"

using namespace clothsim;

TEST_CASE("only plain llvmpipe is bit-exact: zink on lavapipe and GPUs run in tolerance mode") {
  // Mesa 22.3's strings on this machine (docs/testing.md, "The zink lane").
  CHECK(gl::renderer_is_bit_exact("llvmpipe (LLVM 15.0.6, 256 bits)"));
  CHECK_FALSE(gl::renderer_is_bit_exact("zink (llvmpipe (LLVM 15.0.6, 256 bits))"));
  CHECK_FALSE(gl::renderer_is_bit_exact("NVIDIA GeForce RTX 4090/PCIe/SSE2"));
  CHECK_FALSE(gl::renderer_is_bit_exact("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.54, 6.5.0)"));
  CHECK_FALSE(gl::renderer_is_bit_exact("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"));
  CHECK_FALSE(gl::renderer_is_bit_exact("softpipe"));
  CHECK_FALSE(gl::renderer_is_bit_exact(""));
}

TEST_CASE("Mesa's CPU rasterizers, zink on lavapipe included, are software, GPUs are not") {
  CHECK(gl::renderer_is_software("llvmpipe (LLVM 15.0.6, 256 bits)"));
  CHECK(gl::renderer_is_software("zink (llvmpipe (LLVM 15.0.6, 256 bits))"));
  CHECK(gl::renderer_is_software("softpipe"));
  CHECK_FALSE(gl::renderer_is_software("NVIDIA GeForce RTX 4090/PCIe/SSE2"));
  CHECK_FALSE(gl::renderer_is_software("zink (NVIDIA GeForce RTX 4090)"));
  CHECK_FALSE(gl::renderer_is_software("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.54, 6.5.0)"));
}

// Every compute pass of the GPU simulator against its CPU twin (docs/design.md §1, §6): each pass
// alone from an identical state, on a grid within one workgroup (7x5), one of a few (33x17)
// and one wider and taller than a workgroup (131x129); whole runs; pins; determinism; collider
// arrays; other settings. On llvmpipe the reference rounds exactly like the shaders, so
// "matches" means bit for bit there; on other GPUs (FMA, approximate sqrt and division) it
// means within the stated tolerances.
#include "gpu_pass_fixtures.hpp"

TEST_CASE("each GPU pass matches the reference from an identical state on a 7x5 cloth", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_passes_on_grid(7, 5);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("each GPU pass matches the reference from an identical state on a 33x17 cloth", "[gpu]") {
  REQUIRE_GL_CONTEXT();
  check_passes_on_grid(33, 17);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("each GPU pass matches the reference from an identical state on a 131x129 cloth, "
          "wider and taller than a workgroup",
          "[gpu]") {
  REQUIRE_GL_CONTEXT();
  static_assert(WORKGROUP_SIZE < 129, "the grid must be larger than a workgroup in both directions");
  check_passes_on_grid(131, 129);
  CHECK_NO_GL_ERRORS();
}

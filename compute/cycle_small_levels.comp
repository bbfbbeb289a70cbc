// Reads positions and the offsets (through their views) and the residuals of the first small
// level's children; reads and writes the right-hand sides, residuals and corrections of the
// small levels. One workgroup runs the small levels' part of the V-cycle (docs/model.md): each
// small level restricted in turn, kCoarsestSweeps Gauss-Seidel sweeps of the coarsest, then
// each level prolonged and swept once on the way back up, the invocations striding over a
// level's vertices or a colour's, a barrier between each step and the next. These levels
// (kSmallLevelVertices) are too small for a dispatch per level and colour to pay: this is one.
// The CPU twin is cycle_small_levels in host/core/reference/reference_multigrid.cpp, the same steps
// (coarse_levels.glsl) in the same order.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
// coherent, and read in place: each step reads what the step before it wrote, in this dispatch.
layout(std430, binding = BINDING_MG_RESIDUALS) coherent buffer Residuals { vec4 residual[]; };
layout(std430, binding = BINDING_MG_RHS) coherent buffer Rhs { vec4 rhs[]; };
layout(std430, binding = BINDING_MG_CORR) coherent buffer Corrections { vec4 corr[]; };
#define MG_RESIDUAL_OF(k) residual[k]
#define MG_RHS_OF(g) rhs[g]
#define MG_CORR_OF(g) corr[g]
#include "multigrid.glsl"
#include "coarse_levels.glsl"

// The small levels' table, at entry u_first of the order's view (GpuSimulator::ensure_multigrid):
// the level count L, then per level (first small one first) the entry of its row; a row is its
// first vertex, its vertex count, its colour count C and C + 1 colour starts (order entries).
uint table(uint k) { return texelFetch(mg_order_view, int(u_first + k)).x; }

// The next step reads what this one wrote.
void step_done() {
  memoryBarrierBuffer();
  barrier();
}

// `sweeps` Gauss-Seidel sweeps over the colours of the level whose row is at `row`.
void smooth_level(uint row, uint sweeps) {
  uint colours = table(row + 2u);
  for (uint it = 0u; it < sweeps; ++it)
    for (uint k = 0u; k < colours; ++k) {
      uint last = table(row + 4u + k);
      for (uint e = table(row + 3u + k) + gl_LocalInvocationID.x; e < last; e += uint(WORKGROUP_SIZE))
        smooth_vertex(texelFetch(mg_order_view, int(e)).x);
      step_done();
    }
}

void main() {
  uint levels = table(0u);
  // Down: restrict each small level from the one above it.
  for (uint l = 0u; l < levels; ++l) {
    uint row = table(1u + l), first = table(row), last = first + table(row + 1u);
    for (uint g = first + gl_LocalInvocationID.x; g < last; g += uint(WORKGROUP_SIZE)) restrict_vertex(g);
    step_done();
  }
  // The coarsest level (solve_coarsest).
  smooth_level(table(levels), uint(COARSEST_SWEEPS));
  // Up: prolong to each small level from the one below it, then one sweep there.
  for (uint l = levels - 1u; l-- > 0u;) {
    uint row = table(1u + l), first = table(row), last = first + table(row + 1u);
    for (uint g = first + gl_LocalInvocationID.x; g < last; g += uint(WORKGROUP_SIZE)) prolong_vertex(g);
    step_done();
    smooth_level(row, uint(LEVEL_SWEEPS));
  }
}

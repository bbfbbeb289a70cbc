// Reads positions and the right-hand sides (through the views); reads and writes the corrections
// of the coarsest level. One workgroup: kCoarsestSweeps Gauss-Seidel sweeps over the level's
// colours, the invocations striding over each colour's vertices, a barrier between colours, so the
// whole coarsest solve is one dispatch (the level is small: at most a few hundred vertices). The
// CPU twin is solve_coarsest in host/core/reference_multigrid.cpp (smooth_corrections, colour by
// colour, in the same arithmetic).
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
// coherent: a colour reads the corrections the colour before it wrote, within this dispatch.
layout(std430, binding = BINDING_MG_CORR) coherent buffer Corrections { vec4 corr[]; };
#define MG_CORR_OF(g) corr[g]
#include "multigrid.glsl"

// u_first: the level's first colour in the order; u_count: its colour count; the colour starts
// follow in u_starts (COARSEST_COLOURS_MAX of them at most, set by the host).
#define COARSEST_COLOURS_MAX 32
uniform uint u_starts[COARSEST_COLOURS_MAX + 1];
uniform uint u_sweeps;

void main() {
  for (uint it = 0u; it < u_sweeps; ++it)
    for (uint k = 0u; k < u_count; ++k) {
      for (uint e = u_starts[k] + gl_LocalInvocationID.x; e < u_starts[k + 1u]; e += uint(WORKGROUP_SIZE)) {
        uint g = texelFetch(mg_order_view, int(e)).x;
        uvec4 v = mg_vertex(g);
        vec4 b = rhs_of(g);
        if (b.w < 0.0) continue;  // a fixed vertex does not move (restrict_residuals)
        Sym3 diag;
        vec3 r = coarse_residual(g, v, b, diag);
        vec3 step;
        if (solve3(diag, r, step)) {
          precise vec3 next = corr[g].xyz + step;
          corr[g] = vec4(next, 0.0);
        }
      }
      // The next colour reads these corrections.
      memoryBarrierBuffer();
      barrier();
    }
}

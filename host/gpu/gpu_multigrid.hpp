// The multigrid solver's GPU resources (gpu_multigrid.cpp): its passes' programs, the
// hierarchy's lists and the scratch of a solve, with their views.
#pragma once

#include <memory>
#include <string>

#include <fmt/format.h>

#include "gpu_simulator.hpp"

namespace clothsim {

inline gl::Program load_multigrid_pass(const std::filesystem::path& dir, const char* name,
                                      const ShaderFeatures& features) {
  return load_pass(dir, name, features,
                   {{"CONTACT_REACH", fmt::format("{:.9e}", float(kContactReach))},
                    {"FOLDED_CHORD", fmt::format("{:.9e}", float(kFoldedChord))},
                    {"COARSEST_SWEEPS", std::to_string(kCoarsestSweeps)},
                    {"LEVEL_SWEEPS", std::to_string(kLevelSweeps)}});
}

// A pass dispatched over a range (u_first, u_count): its uniforms' locations, looked up once.
struct GpuMultigridPass {
  gl::Program& program;
  GLint first, count;
  explicit GpuMultigridPass(gl::Program& p) : program(p), first(p.location("u_first")), count(p.location("u_count")) {}
};

struct GpuMultigrid {
  GpuMultigrid(const std::filesystem::path& dir, const ShaderFeatures& f)
      : compute_residuals(load_multigrid_pass(dir, "compute_residuals", f)),
        restrict_residuals(load_multigrid_pass(dir, "restrict_residuals", f)),
        smooth_corrections(load_multigrid_pass(dir, "smooth_corrections", f)),
        cycle_small_levels(load_multigrid_pass(dir, "cycle_small_levels", f)),
        prolong_corrections(load_multigrid_pass(dir, "prolong_corrections", f)),
        prolong_to_cloth(load_multigrid_pass(dir, "prolong_to_cloth", f)),
        relax_vertices(load_multigrid_pass(dir, "relax_vertices", f)) {}
  gl::Program compute_residuals, restrict_residuals, smooth_corrections, cycle_small_levels, prolong_corrections,
      prolong_to_cloth, relax_vertices;
  GpuMultigridPass restrict_residuals_range{restrict_residuals}, smooth_corrections_range{smooth_corrections};
  GpuMultigridPass prolong_corrections_range{prolong_corrections}, relax_vertices_range{relax_vertices};
  // The hierarchy (layout.glsl: TEXTURE_MG_VERTICES, _LISTS, _FINE, _ORDER), static over a run.
  gl::Buffer vertices{"multigrid vertices"}, lists{"multigrid lists"}, fine{"multigrid fine parents"}, order{"multigrid order"};
  // A solve's scratch (BINDING_MG_RESIDUALS, _OFFSET, _RHS, _CORR).
  gl::Buffer residuals{"multigrid residuals"}, offset{"multigrid offsets"}, rhs{"multigrid rhs"}, corr{"multigrid corrections"};
  gl::BufferTexture vertices_view{"multigrid vertices view"}, lists_view{"multigrid lists view"};
  gl::BufferTexture fine_view{"multigrid fine parents view"}, order_view{"multigrid order view"};
  gl::BufferTexture corr_view{"multigrid corrections view"}, offset_view{"multigrid offsets view"};
  gl::BufferTexture residuals_view{"multigrid residuals view"}, rhs_view{"multigrid rhs view"};
  std::shared_ptr<const Hierarchy> hierarchy;  // what the buffers hold (Constants::hierarchy)
};

}  // namespace clothsim

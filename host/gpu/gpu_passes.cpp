// The passes' programs, loaded from the pass table's rows; one dispatch of a row; the counts.
#include "gpu_passes.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "debug_output.hpp"
#include "gpu_multigrid.hpp"

namespace clothsim {
namespace {

// The defines a row's build adds to the shader features'.
gl::Defines defines_for(Build build) {
  switch (build) {
    case Build::listed: return {{"LISTED", "1"}};
    case Build::multigrid:
      return {{"CONTACT_REACH", fmt::format("{:.9e}", float(kContactReach))},
              {"COARSEST_SWEEPS", std::to_string(kCoarsestSweeps)},
              {"LEVEL_SWEEPS", std::to_string(kLevelSweeps)}};
    case Build::settling:
      return {{"STRETCH_SETTLED", "(1.0 + 1.0 / " + std::to_string(1 << kStretchSettledBits) + ".0)"}};
    default: return {};
  }
}

}  // namespace

GpuPasses::GpuPasses(GpuState& state, const Constants<float>& constants, const Scene& scene, const ClothModel& model,
                     const std::filesystem::path& dir)
    : state_(state),
      constants_(constants),
      dir_(dir),
      groups_(gl::workgroups_for(model.count(), WORKGROUP_SIZE)),
      scan_(dir, hash_table_size(uint32_t(model.count()))),
      guard_(scene, model, dir) {
  load_passes(ShaderFeatures::of(constants_));
}

GpuPasses::~GpuPasses() = default;

void GpuPasses::load_passes(const ShaderFeatures& features) {
  features_ = features;
  for (Build build : {Build::always, Build::listed}) load_rows(build);
  state_.multigrid_.reset();         // its rows too, on first use (ensure_multigrid)
  settling_loaded_ = false;   // and enforce_stretch_limit's watched pass (settling_passes)
}

void GpuPasses::load_rows(Build build) {
  for (const PassRow& r : kPasses) {
    if (r.build != build) continue;
    const size_t i = size_t(r.id);
    gl::Program& p = programs_[i] = load_pass(dir_, r.file, features_, defines_for(build));
    if (r.domain == Domain::colour || r.domain == Domain::range || r.domain == Domain::stretch_control) {
      first_[i] = p.location("u_first");
      count_[i] = p.location("u_count");
    }
    if (r.flag_uniform) flag_[i] = p.location(r.flag_uniform);
  }
}

void GpuPasses::dispatch_row(PassId pass, PassSpan span, bool listed, GLintptr indirect) {
  const PassRow& r = row(pass);
  const size_t i = size_t(r.program_of);
  gl::Program& p = programs_[i];
  switch (r.domain) {
    case Domain::particles: p.dispatch(groups_); break;
    case Domain::skinned_vertices: p.dispatch(gl::workgroups_for(constants_.skin_vertices, WORKGROUP_SIZE)); break;
    case Domain::skin_supers: p.dispatch(gl::workgroups_for(constants_.skin_supers, WORKGROUP_SIZE)); break;
    case Domain::hash_table: p.dispatch(gl::workgroups_for(state_.table_size_, WORKGROUP_SIZE)); break;
    case Domain::colour:
      if (span.count == 0) return;  // a grid too narrow for this colour: nothing, not even the barrier
      [[fallthrough]];
    case Domain::range:
      if (span.count > 0) {
        p.set(first_[i], span.first);
        p.set(count_[i], span.count);
        p.dispatch(gl::workgroups_for(span.count, WORKGROUP_SIZE));
      }
      break;
    case Domain::contact_list:
      state_.contacts_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CONTACT_LIST);
      state_.contacts_.bind(GL_DISPATCH_INDIRECT_BUFFER);
      p.dispatch_indirect(0);
      break;
    case Domain::stretch_control:
      p.set(first_[i], span.first);
      p.set(count_[i], span.count);
      p.dispatch_indirect(indirect);
      break;
    case Domain::one_workgroup: p.dispatch(1); break;
    case Domain::scan: return;  // the scan dispatches and counts its own
  }
  if (r.domain != Domain::range || span.count > 0) dispatched(p);
  barrier(r.barrier | (listed ? r.listed_barrier : 0));
}

void GpuPasses::dispatched([[maybe_unused]] const gl::Program& program) {
  ++counters_.dispatches;
#ifndef NDEBUG
  // Debug builds look after every pass, so a GL error names the pass that raised it (KHR_debug
  // has printed the failing call already). Release builds look once per frame (step_frame).
  gl::check_gl_errors_lazily([&] {
    return in_frame_ ? fmt::format("after the pass {} (substep {} of frame {})", program.name(), substep_ + 1,
                                   guard_.frame() + 1)
                     : fmt::format("after the pass {}", program.name());
  });
#endif
}

void GpuPasses::barrier(GLbitfield bits) {
  glMemoryBarrier(bits);
  ++counters_.barriers;
}

GpuCounters GpuPasses::counters() const {
  return {counters_.dispatches + scan_.counters().dispatches + guard_.counters().dispatches,
          counters_.barriers + scan_.counters().barriers + guard_.counters().barriers};
}

SubstepShape GpuPasses::shape() const {
  const Constants<float>& c = constants_;
  SubstepShape s;
  s.features = features();
  for (int colour = 0; colour < state_.model_.colours(); ++colour) s.enabled_colours += enabled_colour(colour);
  s.iterations = c.iterations;
  s.scan_dispatches = c.self_collision ? scan_.dispatches(state_.table_size_) : 0;
  s.stretch_passes = c.stretch_passes;
  s.stretch_passes_max = c.stretch_passes_max;
  if (!c.multigrid) return s;
  const Hierarchy& h = *c.hierarchy;
  s.fine_colours = h.fine_colours();  // (relax_vertices pushes out inline: no listed colours)
  if (h.levels.empty()) return s;
  s.large_levels = first_small_level(h);
  s.levels = int(h.levels.size());
  for (int l = 0; l < s.large_levels; ++l)
    s.large_level_colours += (int(h.levels[size_t(l)].colour_start.size()) - 1) * kLevelSweeps;
  return s;
}

int GpuPasses::dispatches_per_substep() const { return clothsim::dispatches_per_substep(shape()); }

int GpuPasses::multigrid_dispatches() const {
  const SubstepShape s = shape();
  int count = 0;
  for (const PassRow& r : kPasses)
    if (r.build == Build::multigrid) count += dispatches_of(r, s);
  return count;
}

}  // namespace clothsim

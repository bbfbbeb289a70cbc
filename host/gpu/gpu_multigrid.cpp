// The multigrid solver's passes on the GPU (docs/model.md, "One substep (fabric solver)"),
// each named like its .comp file and its CPU twin in host/core/reference/reference_multigrid.cpp, and the
// hierarchy's buffers. Made on first use, so a run of another solver compiles none of it.
#include "gpu_multigrid.hpp"
#include "gpu_passes.hpp"

#include <bit>

#include <fmt/format.h>

namespace clothsim {

namespace {

uint32_t bits(double v) { return std::bit_cast<uint32_t>(float(v)); }

}  // namespace

void GpuPasses::ensure_multigrid() {
  if (!constants_.multigrid) return;
  const Hierarchy& h = *constants_.hierarchy;
  if (state_.multigrid_ && state_.multigrid_->hierarchy == constants_.hierarchy) return;
  if (!state_.multigrid_) {
    state_.multigrid_ = std::make_unique<GpuMultigrid>();
    load_rows(Build::multigrid);
  }
  GpuMultigrid& g = *state_.multigrid_;
  const uint32_t n = uint32_t(state_.model_.count()), coarse = h.coarse_count();
  // The lists: every coarse vertex's children, then parents, then springs, then the particles' parents.
  std::vector<glm::uvec4> lists;
  const uint32_t parents_at = uint32_t(h.child.size()), springs_at = parents_at + uint32_t(h.parent.size());
  const uint32_t fine_at = springs_at + uint32_t(h.spring_other.size());
  for (size_t k = 0; k < h.child.size(); ++k) lists.push_back({h.child[k], bits(h.child_weight[k]), 0u, 0u});
  for (size_t k = 0; k < h.parent.size(); ++k) lists.push_back({h.parent[k], bits(h.parent_weight[k]), 0u, 0u});
  for (size_t k = 0; k < h.spring_other.size(); ++k)
    lists.push_back({h.spring_other[k], bits(h.spring_rest[k]), bits(h.spring_k[k]), h.particle[h.spring_other[k]]});
  for (size_t k = 0; k < h.fine_parent.size(); ++k) lists.push_back({h.fine_parent[k], bits(h.fine_parent_weight[k]), 0u, 0u});
  std::vector<glm::uvec4> vertices;
  for (uint32_t v = 0; v <= coarse; ++v)
    vertices.push_back({v < coarse ? h.particle[v] : 0u, h.child_start[v], parents_at + h.parent_start[v],
                        springs_at + h.spring_start[v]});
  std::vector<uint32_t> fine;
  for (uint32_t i = 0; i <= n; ++i) fine.push_back(fine_at + h.fine_parent_start[i]);
  fine.insert(fine.end(), h.fine_colour.begin(), h.fine_colour.end());  // relax_vertices' self-contacts
  std::vector<uint32_t> order = h.fine_order;
  order.insert(order.end(), h.order.begin(), h.order.end());
  // cycle_small_levels' table after the order (compute/cycle_small_levels.comp): the small
  // levels' count, each one's row entry, then the rows (first vertex, vertex count, colour
  // count, colour starts as order entries).
  const uint32_t table_at = uint32_t(order.size());
  if (!h.levels.empty()) {
    const uint32_t small = uint32_t(first_small_level(h)), levels = uint32_t(h.levels.size());
    std::vector<uint32_t> table{levels - small}, rows;
    for (uint32_t l = small; l < levels; ++l) {
      const HierarchyLevel& level = h.levels[l];
      // Its row's entry, from the table's start (as the shader's table() reads): after the
      // count, the levels' entries and the rows before it.
      table.push_back(1 + (levels - small) + uint32_t(rows.size()));
      rows.insert(rows.end(), {level.first, level.count, uint32_t(level.colour_start.size()) - 1});
      for (uint32_t start : level.colour_start) rows.push_back(n + start);
    }
    table.insert(table.end(), rows.begin(), rows.end());
    order.insert(order.end(), table.begin(), table.end());
  }
  // A storage buffer or view may not be empty: one dummy element for a model without coarse levels.
  auto nonempty = [](auto v) { if (v.empty()) v.resize(1); return v; };
  gl::upload_vector(g.vertices, vertices, GL_STATIC_DRAW);
  gl::upload_vector(g.lists, nonempty(lists), GL_STATIC_DRAW);
  gl::upload_vector(g.fine, fine, GL_STATIC_DRAW);
  gl::upload_vector(g.order, nonempty(order), GL_STATIC_DRAW);
  g.residuals.allocate(size_t(n + coarse) * sizeof(glm::vec4));
  g.offset.allocate(size_t(n) * sizeof(glm::vec4));
  g.rhs.allocate(std::max<size_t>(1, coarse) * sizeof(glm::vec4));
  g.corr.allocate(std::max<size_t>(1, coarse) * sizeof(glm::vec4));
  g.residuals.clear_to_zero();
  g.offset.clear_to_zero();
  g.rhs.clear_to_zero();
  g.corr.clear_to_zero();
  g.vertices_view.attach(g.vertices, GL_RGBA32UI);
  g.lists_view.attach(g.lists, GL_RGBA32UI);
  g.fine_view.attach(g.fine, GL_R32UI);
  g.order_view.attach(g.order, GL_R32UI);
  g.corr_view.attach(g.corr, GL_RGBA32F);
  g.offset_view.attach(g.offset, GL_RGBA32F);
  g.residuals_view.attach(g.residuals, GL_RGBA32F);
  g.rhs_view.attach(g.rhs, GL_RGBA32F);
  programs_[size_t(PassId::cycle_small_levels)].set("u_first", table_at);  // where its table starts, fixed with the hierarchy
  g.hierarchy = constants_.hierarchy;
  state_.bind_multigrid();
}

// restrict_residuals and prolong_corrections over a level's vertices, smooth_corrections over
// one of its colours (or `sweeps` sweeps of every colour), relax_vertices over a fine colour
// (or every one), its push-out inline (relax_vertices.comp).
void GpuPasses::level_pass(PassId pass, const PassArgs& a) {
  const Hierarchy& h = *constants_.hierarchy;
  if (pass == PassId::relax_vertices || pass == PassId::smooth_corrections) {
    const bool fine = pass == PassId::relax_vertices;
    const std::vector<uint32_t>& starts = fine ? h.fine_colour_start : h.levels[size_t(a.level)].colour_start;
    if (a.colour < 0) {
      for (int it = 0; it < (fine ? 1 : a.sweeps); ++it)
        for (int k = 0; k + 1 < int(starts.size()); ++k) level_pass(pass, {a.level, k});
      return;
    }
    const uint32_t first = starts[size_t(a.colour)], last = starts[size_t(a.colour) + 1];
    // The coarse vertices follow the particles in the multigrid's buffers.
    dispatch_row(pass, {(fine ? 0u : uint32_t(state_.model_.count())) + first, last - first});
    return;
  }
  const HierarchyLevel& l = h.levels[size_t(a.level)];
  dispatch_row(pass, {l.first, l.count});
}

void GpuPasses::cycle_levels() {
  const int levels = int(constants_.hierarchy->levels.size()), small = first_small_level(*constants_.hierarchy);
  if (levels == 0) return;
  for (int l = 0; l < small; ++l) run(PassId::restrict_residuals, {.level = l});
  run(PassId::cycle_small_levels);
  for (int l = small - 1; l >= 0; --l) {
    run(PassId::prolong_corrections, {.level = l});
    run(PassId::smooth_corrections, {.level = l, .sweeps = kLevelSweeps});
  }
}

void GpuPasses::solve_multigrid() {
  run(PassId::compute_residuals);
  cycle_levels();
  run(PassId::prolong_to_cloth);
  run(PassId::relax_vertices);
}

void GpuPasses::download_multigrid(State<float>& s) {
  ensure_multigrid();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const GpuMultigrid& g = *state_.multigrid_;
  const size_t coarse = constants_.hierarchy->coarse_count();
  s.residual = gl::download_vector<Vec4<float>>(g.residuals);
  s.coarse_rhs = gl::download_vector<Vec4<float>>(g.rhs, 0, coarse);
  s.coarse_corr = gl::download_vector<Vec4<float>>(g.corr, 0, coarse);
}

void GpuPasses::upload_multigrid(const State<float>& s) {
  ensure_multigrid();
  GpuMultigrid& g = *state_.multigrid_;
  const size_t coarse = constants_.hierarchy->coarse_count();
  if (s.residual.size() == state_.model_.count() + coarse) g.residuals.upload(0, s.residual.size() * sizeof(glm::vec4), s.residual.data());
  if (s.coarse_rhs.size() == coarse && coarse > 0) g.rhs.upload(0, coarse * sizeof(glm::vec4), s.coarse_rhs.data());
  if (s.coarse_corr.size() == coarse && coarse > 0) g.corr.upload(0, coarse * sizeof(glm::vec4), s.coarse_corr.data());
}

}  // namespace clothsim

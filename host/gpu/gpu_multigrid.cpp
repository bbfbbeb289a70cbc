// The multigrid solver's passes on the GPU (docs/model.md, "One substep (multigrid solver)"),
// each named like its .comp file and its CPU twin in host/core/reference/reference_multigrid.cpp, and the
// hierarchy's buffers. Made on first use, so a run of another solver compiles none of it.
#include "gpu_multigrid.hpp"

#include <bit>

#include <fmt/format.h>

namespace clothsim {

namespace {

uint32_t bits(double v) { return std::bit_cast<uint32_t>(float(v)); }

}  // namespace

void GpuSimulator::ensure_multigrid() {
  if (!constants_.multigrid) return;
  const Hierarchy& h = *constants_.hierarchy;
  if (multigrid_ && multigrid_->hierarchy == constants_.hierarchy) return;
  if (!multigrid_) multigrid_ = std::make_unique<GpuMultigrid>(dir_, features_);
  GpuMultigrid& g = *multigrid_;
  const uint32_t n = uint32_t(model_.count()), coarse = h.coarse_count();
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
  g.cycle_small_levels.set("u_first", table_at);  // where its table starts, fixed with the hierarchy
  g.hierarchy = constants_.hierarchy;
  bind_multigrid();
}

void GpuSimulator::bind_multigrid() const {
  if (!multigrid_) {
    // predict declares the offsets (it writes them only for the multigrid solver): a binding
    // of one element stands in for them.
    no_offsets_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MG_OFFSET);
    return;
  }
  const GpuMultigrid& g = *multigrid_;
  g.residuals.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MG_RESIDUALS);
  g.offset.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MG_OFFSET);
  g.rhs.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MG_RHS);
  g.corr.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MG_CORR);
  g.vertices_view.bind(TEXTURE_MG_VERTICES);
  g.lists_view.bind(TEXTURE_MG_LISTS);
  g.fine_view.bind(TEXTURE_MG_FINE);
  g.order_view.bind(TEXTURE_MG_ORDER);
  g.corr_view.bind(TEXTURE_MG_CORR);
  g.offset_view.bind(TEXTURE_MG_OFFSET);
  g.residuals_view.bind(TEXTURE_MG_RESIDUALS);
  g.rhs_view.bind(TEXTURE_MG_RHS);
}

// One dispatch of a multigrid pass over items [first, first + count) (u_first, u_count, their
// locations looked up once in GpuMultigrid).
void GpuSimulator::dispatch_range(GpuMultigridPass& pass, uint32_t first, uint32_t count) {
  if (count == 0) return;
  pass.program.set(pass.first, first);
  pass.program.set(pass.count, count);
  pass.program.dispatch(gl::workgroups_for(count, WORKGROUP_SIZE));
  dispatched(pass.program);
}

void GpuSimulator::compute_residuals() {
  ensure_multigrid();
  bind_for_pass();
  dispatch(multigrid_->compute_residuals);
  // restrict_residuals reads them (through their view) next.
  barrier(kComputeReads);
}

void GpuSimulator::restrict_residuals(int level) {
  ensure_multigrid();
  bind_for_pass();
  const HierarchyLevel& l = constants_.hierarchy->levels[size_t(level)];
  dispatch_range(multigrid_->restrict_residuals_range, l.first, l.count);
  // smooth_corrections reads the right-hand sides and the zeroed corrections next.
  barrier(kComputeReads);
}

void GpuSimulator::smooth_corrections(int level, int colour) {
  ensure_multigrid();
  bind_for_pass();
  const HierarchyLevel& l = constants_.hierarchy->levels[size_t(level)];
  const uint32_t first = l.colour_start[size_t(colour)], last = l.colour_start[size_t(colour) + 1];
  dispatch_range(multigrid_->smooth_corrections_range, uint32_t(model_.count()) + first, last - first);
  // The next colour reads these corrections through their view.
  barrier(kComputeReads);
}

void GpuSimulator::cycle_small_levels() {
  ensure_multigrid();
  if (constants_.hierarchy->levels.empty()) return;
  bind_for_pass();
  // Its table (levels, vertices, colours) is set with the hierarchy (ensure_multigrid).
  gl::Program& p = multigrid_->cycle_small_levels;
  p.dispatch(1);  // one workgroup: its barriers order the steps
  dispatched(p);
  // prolong_corrections (or prolong_to_cloth) reads the corrections through their view next.
  barrier(kComputeReads);
}

void GpuSimulator::prolong_corrections(int level) {
  ensure_multigrid();
  bind_for_pass();
  const HierarchyLevel& l = constants_.hierarchy->levels[size_t(level)];
  dispatch_range(multigrid_->prolong_corrections_range, l.first, l.count);
  // smooth_corrections reads the corrections through their view next.
  barrier(kComputeReads);
}

void GpuSimulator::prolong_to_cloth() {
  ensure_multigrid();
  bind_for_pass();
  dispatch(multigrid_->prolong_to_cloth);
  // relax_vertices reads the positions (views), displacements and offsets next.
  barrier(kComputeReads);
}

void GpuSimulator::relax_vertices(int colour) {
  ensure_multigrid();
  bind_for_pass();
  const Hierarchy& h = *constants_.hierarchy;
  const uint32_t first = h.fine_colour_start[size_t(colour)], last = h.fine_colour_start[size_t(colour) + 1];
  const bool listed = uses_contact_list() && last > first;
  if (listed) start_contact_list();
  dispatch_range(multigrid_->relax_vertices_range, first, last - first);
  // The next colour (or the next substep's first pass) reads these positions and displacements,
  // or first collide_objects the listed ones, its workgroups from the list's header (COMMAND).
  barrier(kComputeReads | (listed ? GL_COMMAND_BARRIER_BIT : 0));
  if (listed) collide_listed(false);
}

void GpuSimulator::smooth_level(int level, int sweeps) {
  const int colours = int(constants_.hierarchy->levels[size_t(level)].colour_start.size()) - 1;
  for (int it = 0; it < sweeps; ++it)
    for (int k = 0; k < colours; ++k) smooth_corrections(level, k);
}

void GpuSimulator::cycle_levels() {
  const int levels = int(constants_.hierarchy->levels.size()), small = first_small_level(*constants_.hierarchy);
  if (levels == 0) return;
  for (int l = 0; l < small; ++l) restrict_residuals(l);
  cycle_small_levels();
  for (int l = small - 1; l >= 0; --l) {
    prolong_corrections(l);
    smooth_level(l, kLevelSweeps);
  }
}

void GpuSimulator::solve_multigrid() {
  compute_residuals();
  cycle_levels();
  prolong_to_cloth();
  for (int k = 0; k < constants_.hierarchy->fine_colours(); ++k) relax_vertices(k);
}

int GpuSimulator::multigrid_dispatches() const {
  const Hierarchy& h = *constants_.hierarchy;
  const int levels = int(h.levels.size());
  int count = 2 + h.fine_colours();  // compute_residuals, prolong_to_cloth, the sweep's colours
  // and after each colour its push-out over the contact list (gpu_contacts.cpp), where used.
  if (uses_contact_list())
    for (int k = 0; k < h.fine_colours(); ++k) count += h.fine_colour_start[size_t(k) + 1] > h.fine_colour_start[size_t(k)];
  if (levels == 0) return count;
  const int small = first_small_level(h);
  count += small + 1;  // restrict_residuals per large level, cycle_small_levels
  for (int l = 0; l < small; ++l)
    count += 1 + (int(h.levels[size_t(l)].colour_start.size()) - 1) * kLevelSweeps;  // prolong, smooth
  return count;
}

void GpuSimulator::download_multigrid(State<float>& s) {
  ensure_multigrid();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const GpuMultigrid& g = *multigrid_;
  const size_t coarse = constants_.hierarchy->coarse_count();
  s.residual = gl::download_vector<Vec4<float>>(g.residuals);
  s.offset = gl::download_vector<Vec4<float>>(g.offset);
  s.coarse_rhs = gl::download_vector<Vec4<float>>(g.rhs, 0, coarse);
  s.coarse_corr = gl::download_vector<Vec4<float>>(g.corr, 0, coarse);
}

void GpuSimulator::upload_multigrid(const State<float>& s) {
  ensure_multigrid();
  GpuMultigrid& g = *multigrid_;
  const size_t coarse = constants_.hierarchy->coarse_count();
  if (s.residual.size() == model_.count() + coarse) g.residuals.upload(0, s.residual.size() * sizeof(glm::vec4), s.residual.data());
  if (s.offset.size() == size_t(model_.count())) g.offset.upload(0, s.offset.size() * sizeof(glm::vec4), s.offset.data());
  if (s.coarse_rhs.size() == coarse && coarse > 0) g.rhs.upload(0, coarse * sizeof(glm::vec4), s.coarse_rhs.data());
  if (s.coarse_corr.size() == coarse && coarse > 0) g.corr.upload(0, coarse * sizeof(glm::vec4), s.coarse_corr.data());
}

size_t GpuSimulator::multigrid_memory_bytes() const {
  if (!multigrid_) return 0;
  const GpuMultigrid& g = *multigrid_;
  size_t total = 0;
  for (const gl::Buffer* b : {&g.vertices, &g.lists, &g.fine, &g.order, &g.residuals, &g.offset, &g.rhs, &g.corr})
    total += b->size();
  return total;
}


}  // namespace clothsim

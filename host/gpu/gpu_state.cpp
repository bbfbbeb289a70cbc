// The GPU's state: the buffers, their views and bindings, the model's upload and the hash's
// transfers (gpu_state.hpp).
#include "gpu_state.hpp"

#include <algorithm>
#include <bit>

#include <fmt/format.h>

#include "gpu_memory.hpp"
#include "gpu_multigrid.hpp"

namespace clothsim {
namespace {

// Too large a cloth is bad input, reported before any allocation rather than as a driver
// failure: every per-particle buffer must fit one storage block, every dispatch the group count.
void check_gpu_limits(const Scene& scene, const ClothModel& m) {
  GLint64 max_block = 0;
  GLint max_groups = 0, max_texels = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups);
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  // The largest view and buffer: the gather list (an entry per spring end) or the springs.
  const uint64_t texels = std::max<uint64_t>(m.gather.size() + 2 * (m.membrane.size() + m.hinges.size()) + m.bend.size() / 2, m.count());
  const uint64_t largest = std::max<uint64_t>(m.springs.size() * sizeof(layout::SpringTexel), m.count() * sizeof(glm::vec4));
  const uint64_t groups = std::max<uint64_t>((uint64_t(hash_table_size(uint32_t(m.count()))) + WORKGROUP_SIZE - 1) / WORKGROUP_SIZE,
                                             (m.springs.size() + WORKGROUP_SIZE - 1) / WORKGROUP_SIZE);
  const std::string grid = m.is_grid() ? fmt::format("a {}x{} grid", m.nw, m.nh)
                                       : fmt::format("a cloth of {} particles and {} springs", m.count(), m.springs.size());
  if (max_block > 0 && largest > uint64_t(max_block))
    throw SceneError(fmt::format("{}: cloth.num_width_points: {} needs {} bytes in one storage buffer, more than "
                                 "this GPU's GL_MAX_SHADER_STORAGE_BLOCK_SIZE ({} bytes)",
                                 scene.source, grid, largest, max_block));
  if (max_groups > 0 && groups > uint64_t(max_groups))
    throw SceneError(fmt::format("{}: cloth.num_width_points: {} needs {} workgroups in one dispatch, more than "
                                 "this GPU's GL_MAX_COMPUTE_WORK_GROUP_COUNT ({})",
                                 scene.source, grid, groups, max_groups));
  if (max_texels > 0 && texels > uint64_t(max_texels))
    throw SceneError(fmt::format("{}: cloth.num_width_points: {} needs a texel view of {} texels, more than "
                                 "this GPU's GL_MAX_TEXTURE_BUFFER_SIZE ({})",
                                 scene.source, grid, texels, max_texels));
  check_gpu_memory(scene, m);  // where the driver reports free memory (gpu_memory.hpp)
}

}  // namespace

GpuState::GpuState(const Scene& scene, const ClothModel& model) : model_((check_gpu_limits(scene, model), model)) {}

GpuState::~GpuState() = default;  // here, where GpuMultigrid is whole

size_t GpuState::buffer_bytes() const {
  size_t total = 0;
  for (const gl::Buffer* b : {&positions_, &displacement_, &forces_, &normals_, &springs_, &spheres_, &planes_,
                              &step_params_, &substep_control_, &positions_out_, &cell_count_, &cell_start_, &cell_entries_,
                              &sorted_positions_, &wind_forces_, &anchors_, &gather_start_, &gather_,
                              &particles_, &materials_, &corner_start_, &corner_triangles_, &triangles_, &rest_positions_, &attachments_,
                              &meshes_, &sdf_, &stretch_control_, &contacts_, &skinned_, &skin_indices_,
                              &skin_weights_, &skin_palette_, &nearest_})
    total += b->size();
  if (!multigrid_) return total;
  const GpuMultigrid& g = *multigrid_;
  for (const gl::Buffer* b : {&g.vertices, &g.lists, &g.fine, &g.order, &g.residuals, &g.offset, &g.rhs, &g.corr})
    total += b->size();
  return total;
}

void GpuState::upload_model() {
  const ClothModel& m = model_;
  // Rest lengths are rounded to float once here, exactly as the float reference rounds them.
  std::vector<layout::SpringTexel> springs;
  for (const Spring& s : m.springs)
    springs.push_back({{s.i, s.j, std::bit_cast<uint32_t>(float(s.rest)), uint32_t(s.type) | (s.material << 2)}});
  std::vector<glm::uvec4> gather;
  for (uint32_t g : m.gather) {
    // The other end is filled in per particle below; every particle index fits in 30 bits.
    gather.push_back({0u, std::bit_cast<uint32_t>(float(m.springs[g].rest)), 0u, 0u});
  }
  for (uint32_t i = 0; i < uint32_t(m.count()); ++i)
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
      const Spring& s = m.springs[m.gather[g]];
      gather[g].x = (s.i == i ? s.j : s.i) | (uint32_t(s.type) << 30);
    }
  // With a material: each membrane entry as (a, b, area, 0), (dminv), each pair of bending row
  // entries as (other, weight, other, weight), each hinge entry as (others, rest), (weights),
  // after the springs' entries; their starts follow the springs' in the start list
  // (membrane_first, bend_first and hinge_first in particle_views.glsl).
  std::vector<uint32_t> starts = m.gather_start;
  auto bits = [](double v) { return std::bit_cast<uint32_t>(float(v)); };
  if (m.has_material()) {
    const uint32_t membrane_base = uint32_t(gather.size());
    for (const MembraneEntry& e : m.membrane) {
      gather.push_back({e.a, e.b, bits(e.area), 0u});
      gather.push_back({bits(e.dminv[0]), bits(e.dminv[1]), bits(e.dminv[2]), bits(e.dminv[3])});
    }
    const uint32_t bend_base = uint32_t(gather.size());
    for (size_t e = 0; e < m.bend.size(); e += 2)
      gather.push_back({m.bend[e].other, bits(m.bend[e].weight), m.bend[e + 1].other, bits(m.bend[e + 1].weight)});
    const uint32_t hinge_base = uint32_t(gather.size());
    for (const HingeEntry& h : m.hinges) {
      gather.push_back({h.other[0], h.other[1], h.other[2], bits(h.rest)});
      gather.push_back({bits(h.k[0]), bits(h.k[1]), bits(h.k[2]), bits(h.k[3])});
    }
    for (uint32_t s : m.membrane_start) starts.push_back(membrane_base + 2 * s);
    for (uint32_t s : m.bend_start) starts.push_back(bend_base + s / 2);
    for (uint32_t s : m.hinge_start) starts.push_back(hinge_base + 2 * s);
  }
  std::vector<glm::uvec4> triangles;
  for (auto& t : m.triangles) triangles.push_back({t[0], t[1], t[2], 0u});
  // A storage buffer or view may not be empty: one dummy element for a cloth without springs.
  auto nonempty = [](auto v) { if (v.empty()) v.resize(1); return v; };
  gl::upload_vector(springs_, nonempty(springs), GL_STATIC_DRAW);
  gl::upload_vector(gather_, nonempty(gather), GL_STATIC_DRAW);
  gl::upload_vector(gather_start_, starts, GL_STATIC_DRAW);
  gl::upload_vector(triangles_, nonempty(triangles), GL_STATIC_DRAW);
  gl::upload_vector(corner_start_, m.corner_start, GL_STATIC_DRAW);
  gl::upload_vector(corner_triangles_, nonempty(m.corner_triangles), GL_STATIC_DRAW);
}

void GpuState::bind_all() const {
  positions_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS);
  displacement_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DISPLACEMENT);
  forces_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_FORCES);
  normals_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_NORMALS);
  spheres_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SPHERES);
  planes_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_PLANES);
  step_params_.bind_base(GL_UNIFORM_BUFFER, BINDING_STEP_PARAMS);
  substep_control_.bind_base(GL_UNIFORM_BUFFER, BINDING_SUBSTEP_CONTROL);
  positions_out_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS_OUT);
  cell_count_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CELL_COUNT);
  cell_start_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CELL_START);
  cell_entries_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_CELL_ENTRIES);
  sorted_positions_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SORTED_POSITIONS);
  wind_forces_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_WIND_FORCES);
  anchors_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_ANCHORS);
  positions_view_.bind(TEXTURE_POSITIONS);
  displacement_view_.bind(TEXTURE_DISPLACEMENT);
  springs_view_.bind(TEXTURE_SPRINGS);
  gather_start_view_.bind(TEXTURE_GATHER_START);
  gather_view_.bind(TEXTURE_GATHER);
  particles_view_.bind(TEXTURE_PARTICLES);
  materials_view_.bind(TEXTURE_MATERIALS);
  corner_start_view_.bind(TEXTURE_CORNER_START);
  corner_triangles_view_.bind(TEXTURE_CORNER_TRIANGLES);
  triangles_view_.bind(TEXTURE_TRIANGLES);
  spheres_view_.bind(TEXTURE_SPHERES);
  planes_view_.bind(TEXTURE_PLANES);
  cell_start_view_.bind(TEXTURE_CELL_START);
  sorted_positions_view_.bind(TEXTURE_SORTED_POSITIONS);
  rest_positions_view_.bind(TEXTURE_REST_POSITIONS);
  attachments_view_.bind(TEXTURE_ATTACHMENTS);
  meshes_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MESHES);
  meshes_view_.bind(TEXTURE_MESHES);
  meshes_int_view_.bind(TEXTURE_MESHES_INT);
  sdf_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SDF);
  sdf_view_.bind(TEXTURE_SDF);
  nearest_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_NEAREST);
  skinned_view_.bind(TEXTURE_SKINNED);
  skin_indices_view_.bind(TEXTURE_SKIN_INDICES);
  skin_weights_view_.bind(TEXTURE_SKIN_WEIGHTS);
  skin_palette_view_.bind(TEXTURE_SKIN_PALETTE);
  bind_multigrid();
}

void GpuState::attach_views() {
  positions_view_.attach(positions_, GL_RGBA32F);
  positions_out_view_.attach(positions_out_, GL_RGBA32F);
  displacement_view_.attach(displacement_, GL_RGBA32F);
  springs_view_.attach(springs_, GL_RGBA32UI);
  gather_start_view_.attach(gather_start_, GL_R32UI);
  gather_view_.attach(gather_, GL_RGBA32UI);
  particles_view_.attach(particles_, GL_RGBA32F);
  materials_view_.attach(materials_, GL_RGBA32F);
  corner_start_view_.attach(corner_start_, GL_R32UI);
  corner_triangles_view_.attach(corner_triangles_, GL_R32UI);
  triangles_view_.attach(triangles_, GL_RGBA32UI);
  spheres_view_.attach(spheres_, GL_RGBA32F);
  planes_view_.attach(planes_, GL_RGBA32F);
  cell_start_view_.attach(cell_start_, GL_R32UI);
  sorted_positions_view_.attach(sorted_positions_, GL_RGBA32F);
  rest_positions_view_.attach(rest_positions_, GL_RGBA32F);
  meshes_view_.attach(meshes_, GL_RGBA32F);
  meshes_int_view_.attach(meshes_, GL_RGBA32I);
  sdf_view_.attach(sdf_, GL_RGBA32F);
  skinned_view_.attach(skinned_, GL_RGBA32F);
  skin_indices_view_.attach(skin_indices_, GL_RGBA32UI);
  skin_weights_view_.attach(skin_weights_, GL_RGBA32F);
  skin_palette_view_.attach(skin_palette_, GL_RGBA32F);
}

void GpuState::swap_positions() {
  std::swap(positions_, positions_out_);
  std::swap(positions_view_, positions_out_view_);
  // Only these two changed places; every other binding of the step holds.
  positions_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS);
  positions_out_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS_OUT);
  positions_view_.bind(TEXTURE_POSITIONS);
}

void GpuState::bind_multigrid() const {
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

void GpuState::download_hash(SpatialHash& h) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // a read-back, not part of a step
  h.table_size = table_size_;
  h.count = gl::download_vector<uint32_t>(cell_count_);
  h.start = gl::download_vector<uint32_t>(cell_start_);
  h.entries = gl::download_vector<uint32_t>(cell_entries_);
}

void GpuState::upload_hash(const SpatialHash& h) {
  gl::upload_vector(cell_count_, h.count);
  gl::upload_vector(cell_start_, h.start);
  gl::upload_vector(cell_entries_, h.entries);
  attach_views();  // cell_start_view_ follows the reallocated buffer
}

std::vector<glm::vec4> GpuState::download_sorted_positions() {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return gl::download_vector<glm::vec4>(sorted_positions_);
}

std::vector<Vec4<float>> GpuState::download_displacement() const {
  std::vector<Vec4<float>> disp = gl::download_vector<Vec4<float>>(displacement_);
  for (Vec4<float>& d : disp) d.w = 0.f;
  return disp;
}

}  // namespace clothsim

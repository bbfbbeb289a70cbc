// The simulator's buffers and bindings: construction, the GPU's limits, memory and counters.
#include "gpu_simulator.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <unistd.h>

#include <fmt/format.h>

#include "gpu_memory.hpp"
#include "gpu_multigrid.hpp"
#include "gpu_stretch_limit.hpp"

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
  const uint64_t texels = std::max<uint64_t>(m.gather.size(), m.count());
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

GpuSimulator::GpuSimulator(const Scene& scene, const ClothModel& model, const std::filesystem::path& dir)
    : model_((check_gpu_limits(scene, model), model)),
      dir_(dir),
      constants_(make_constants<float>(scene, model)),
      masses_(particle_masses(scene, model)),
      dt_(scene.dt()),
      groups_(gl::workgroups_for(model.count(), WORKGROUP_SIZE)),
      scan_(dir, hash_table_size(uint32_t(model.count()))),
      guard_(scene, model, dir) {
  load_passes(ShaderFeatures::of(constants_));
  const size_t n = model.count();
  upload_model();

  upload_colliders();
  upload_anchors();
  upload_materials();
  step_params_.allocate(sizeof(layout::StepParams), &constants_.params(), GL_DYNAMIC_DRAW);  // as it is
  forces_.allocate(n * sizeof(glm::vec4));
  // A storage buffer may not be empty when bound: one dummy element without wind.
  wind_forces_.allocate((constants_.wind_enabled ? n : 1) * sizeof(glm::vec4));
  // The hash table is sized once; start[table_size] is the total, always n.
  table_size_ = constants_.table_size;
  cell_count_.allocate(table_size_ * sizeof(uint32_t));
  std::vector<uint32_t> start(table_size_ + 1, 0);
  start.back() = uint32_t(n);
  gl::upload_vector(cell_start_, start);
  cell_entries_.allocate(n * sizeof(uint32_t));
  sorted_positions_.allocate(n * sizeof(glm::vec4));
  normals_.allocate(n * sizeof(glm::vec4));
  no_offsets_.allocate(sizeof(glm::vec4));
  upload(initial_state<float>(model));  // attaches the views
  ensure_multigrid();
  compute_normals();
}

GpuSimulator::~GpuSimulator() = default;  // here, where GpuMultigrid and GpuSettlingPasses are whole

void GpuSimulator::load_passes(const ShaderFeatures& features) {
  features_ = features;
  const std::pair<gl::Program*, const char*> passes[] = {
      {&compute_wind_forces_, "compute_wind_forces"}, {&accumulate_forces_, "accumulate_forces"},
      {&integrate_, "integrate"}, {&advance_, "advance"}, {&collide_objects_, "collide_objects"},
      {&solve_length_constraints_, "solve_length_constraints"}, {&compute_normals_, "compute_normals"},
      {&count_cells_, "count_cells"}, {&fill_cells_, "fill_cells"}, {&sort_cells_, "sort_cells"},
      {&resolve_self_contacts_, "resolve_self_contacts"}, {&predict_, "predict"},
      {&solve_distance_constraints_, "solve_distance_constraints"}};
  for (const auto& [program, name] : passes) *program = load_pass(dir_, name, features);
  collide_listed_ = load_pass(dir_, "collide_objects", features, {{"LISTED", "1"}});
  collide_listed_frictionless_ = load_pass(dir_, "collide_objects", features, {{"LISTED", "1"}, {"FRICTIONLESS", "1"}});
  advance_collide_objects_ = advance_.location("u_collide_objects");
  resolve_collide_objects_ = resolve_self_contacts_.location("u_collide_objects");
  predict_collide_objects_ = predict_.location("u_collide_objects");
  length_colour_ = {solve_length_constraints_.location("u_first"), solve_length_constraints_.location("u_count")};
  distance_colour_ = {solve_distance_constraints_.location("u_first"), solve_distance_constraints_.location("u_count")};
  multigrid_.reset();  // its passes too, on first use (ensure_multigrid)
  settling_.reset();   // and enforce_stretch_limit's watched pass (settling_passes)
}

void GpuSimulator::upload_model() {
  const ClothModel& m = model_;
  // Rest lengths are rounded to float once here, exactly as the float reference rounds them.
  std::vector<layout::SpringTexel> springs;
  for (const Spring& s : m.springs)
    springs.push_back({{s.i, s.j, std::bit_cast<uint32_t>(float(s.rest)), uint32_t(s.type) | (s.material << 2)}});
  std::vector<glm::uvec4> gather;
  for (uint32_t g : m.gather) {
    // The other end and the side are filled in per particle below; every particle index fits
    // in 30 bits.
    gather.push_back({0u, std::bit_cast<uint32_t>(float(m.springs[g].rest)), g, 0u});
  }
  for (uint32_t i = 0; i < uint32_t(m.count()); ++i)
    for (uint32_t g = m.gather_start[i]; g < m.gather_start[i + 1]; ++g) {
      const Spring& s = m.springs[m.gather[g]];
      gather[g].x = (s.i == i ? s.j : s.i) | (uint32_t(s.type) << 30);
      gather[g].w = s.i == i ? 1u : 0u;
    }
  std::vector<glm::uvec4> triangles;
  for (auto& t : m.triangles) triangles.push_back({t[0], t[1], t[2], 0u});
  std::vector<glm::vec4> tethers(m.count());
  for (size_t i = 0; i < tethers.size(); ++i)  // a pin index is exact in a float: at most 2^24 particles
    tethers[i] = glm::vec4(float(m.tether_pin[i]), float(m.tether_rest[i]), 0.f, 0.f);
  // A storage buffer or view may not be empty: one dummy element for a cloth without springs.
  auto nonempty = [](auto v) { if (v.empty()) v.resize(1); return v; };
  gl::upload_vector(springs_, nonempty(springs), GL_STATIC_DRAW);
  gl::upload_vector(gather_, nonempty(gather), GL_STATIC_DRAW);
  gl::upload_vector(gather_start_, m.gather_start, GL_STATIC_DRAW);
  gl::upload_vector(triangles_, nonempty(triangles), GL_STATIC_DRAW);
  gl::upload_vector(corner_start_, m.corner_start, GL_STATIC_DRAW);
  gl::upload_vector(corner_triangles_, nonempty(m.corner_triangles), GL_STATIC_DRAW);
  gl::upload_vector(tethers_, tethers, GL_STATIC_DRAW);
  upload_rest_positions();
}

void GpuSimulator::upload_rest_positions() {
  // Only the bounded contact reads them (one dummy texel otherwise: a view may not be empty).
  std::vector<glm::vec4> rest;
  for (const Vec3<float>& r : constants_.rest) rest.push_back({r.x, r.y, r.z, 0.f});
  if (rest.empty()) rest.resize(1);
  gl::upload_vector(rest_positions_, rest, GL_STATIC_DRAW);
  rest_positions_view_.attach(rest_positions_, GL_RGBA32F);
}

void GpuSimulator::upload_multipliers(std::vector<Vec4<float>> multipliers) {
  multipliers.resize(std::max<size_t>(1, model_.springs.size()), Vec4<float>(0));
  gl::upload_vector(multipliers_, multipliers);
  multipliers_view_.attach(multipliers_, GL_RGBA32F);
  meshes_view_.attach(meshes_, GL_RGBA32F);
  meshes_int_view_.attach(meshes_, GL_RGBA32I);
  sdf_view_.attach(sdf_, GL_RGBA32F);
}

void GpuSimulator::upload_materials() {
  std::vector<layout::MaterialTexels> materials;
  for (const MaterialC<float>& mat : constants_.materials)
    materials.push_back({glm::vec4(mat.ks, mat.ks_bending, mat.alpha, mat.alpha_bending),
                         glm::vec4(mat.keep_velocity, float(mat.enabled[0]), float(mat.enabled[1]), float(mat.enabled[2]))});
  std::vector<glm::vec4> particles;
  for (size_t i = 0; i < constants_.mass.size(); ++i) particles.push_back({constants_.mass[i], float(model_.material[i]), 0.f, 0.f});
  gl::upload_vector(materials_, materials, GL_DYNAMIC_DRAW);
  gl::upload_vector(particles_, particles, GL_DYNAMIC_DRAW);
  materials_view_.attach(materials_, GL_RGBA32F);
  particles_view_.attach(particles_, GL_RGBA32F);
}

void GpuSimulator::barrier(GLbitfield bits) {
  glMemoryBarrier(bits);
  ++counters_.barriers;
}

GpuCounters GpuSimulator::counters() const {
  return {counters_.dispatches + scan_.counters().dispatches + guard_.counters().dispatches,
          counters_.barriers + scan_.counters().barriers + guard_.counters().barriers};
}

size_t GpuSimulator::memory_bytes() const {
  size_t total = 0;
  for (const gl::Buffer* b : {&positions_, &displacement_, &forces_, &normals_, &springs_, &spheres_, &planes_,
                              &step_params_, &positions_out_, &cell_count_, &cell_start_, &cell_entries_,
                              &sorted_positions_, &tethers_, &wind_forces_, &anchors_, &gather_start_, &gather_,
                              &particles_, &materials_, &corner_start_, &corner_triangles_, &triangles_, &rest_positions_,
                              &multipliers_, &meshes_, &sdf_, &stretch_control_, &contacts_})
    total += b->size();
  return total + scan_.memory_bytes() + guard_.memory_bytes() + multigrid_memory_bytes();
}

void GpuSimulator::bind_all() const {
  positions_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_POSITIONS);
  displacement_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_DISPLACEMENT);
  forces_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_FORCES);
  normals_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_NORMALS);
  spheres_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SPHERES);
  planes_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_PLANES);
  step_params_.bind_base(GL_UNIFORM_BUFFER, BINDING_STEP_PARAMS);
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
  tethers_view_.bind(TEXTURE_TETHERS);
  rest_positions_view_.bind(TEXTURE_REST_POSITIONS);
  multipliers_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MULTIPLIERS);
  multipliers_view_.bind(TEXTURE_MULTIPLIERS);
  meshes_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_MESHES);
  meshes_view_.bind(TEXTURE_MESHES);
  meshes_int_view_.bind(TEXTURE_MESHES_INT);
  sdf_.bind_base(GL_SHADER_STORAGE_BUFFER, BINDING_SDF);
  sdf_view_.bind(TEXTURE_SDF);
  bind_multigrid();
}

void GpuSimulator::attach_views() {
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
  tethers_view_.attach(tethers_, GL_RGBA32F);
  rest_positions_view_.attach(rest_positions_, GL_RGBA32F);
  multipliers_view_.attach(multipliers_, GL_RGBA32F);
  meshes_view_.attach(meshes_, GL_RGBA32F);
  meshes_int_view_.attach(meshes_, GL_RGBA32I);
  sdf_view_.attach(sdf_, GL_RGBA32F);
}

GpuBackend::GpuBackend(std::unique_ptr<gl::GlContext> context, const Scene& scene, const ClothModel& model,
                       const std::filesystem::path& compute_dir)
    : context_(std::move(context)), model_(model),
      sim_(std::make_unique<GpuSimulator>(scene, model, compute_dir)) {}

ClothSnapshot GpuBackend::snapshot() {
  State<float> s;
  sim_->download(s);
  ClothSnapshot out;
  for (auto& p : s.pos) out.pos.emplace_back(p);
  for (auto& d : s.disp) out.disp.emplace_back(d);
  for (auto& p : s.normal) out.normal.emplace_back(p);
  return out;
}

std::string GpuBackend::name() const { return fmt::format("gpu ({})", gl::gl_renderer_string()); }

std::filesystem::path find_project_root(const std::filesystem::path& hint) {
  namespace fs = std::filesystem;
  auto has_compute = [](const fs::path& p) { return !p.empty() && fs::exists(p / "compute" / "layout.glsl"); };
  if (!hint.empty()) return hint;
  if (const char* env = std::getenv("CLOTHSIM_ROOT"); env && has_compute(env)) return env;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (fs::path p = exe.parent_path(); !p.empty() && p != p.root_path(); p = p.parent_path())
      if (has_compute(p)) return p;
  }
  if (has_compute(CLOTHSIM_SOURCE_DIR)) return CLOTHSIM_SOURCE_DIR;
  throw std::runtime_error(
      "cannot find the project's shader files (compute/layout.glsl): run from the source tree, "
      "pass -r ROOT, or set CLOTHSIM_ROOT");
}

}  // namespace clothsim

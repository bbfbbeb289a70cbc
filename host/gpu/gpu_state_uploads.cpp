// The state's uploads from the constants: the scratch and the hash table (once), the colliders
// (at construction, per substep when one moves, on live edits), the anchors, the rest positions
// and the materials; and two read-backs of the passes' control buffers.
#include "gpu_state.hpp"
#include "gpu_multigrid.hpp"
#include "sdf_texels.hpp"

#include <fmt/format.h>

namespace clothsim {

namespace {

// A collider array as it is (a storage buffer may not be empty when bound: one dummy element
// for none): in place when its size holds (moving colliders, every substep; the views stay
// attached), else made again. True when made again.
template <class T> bool upload_array(gl::Buffer& buffer, const std::vector<T>& items) {
  const std::vector<T> dummy(1);
  const std::vector<T>& v = items.empty() ? dummy : items;
  const size_t bytes = v.size() * sizeof(T);
  if (buffer.size() == bytes) {
    buffer.upload(0, bytes, v.data());
    return false;
  }
  gl::upload_vector(buffer, v, GL_DYNAMIC_DRAW);
  return true;
}

}  // namespace

void GpuState::allocate_scratch(const Constants<float>& c) {
  const size_t n = model_.count();
  forces_.allocate(n * sizeof(glm::vec4));
  // A storage buffer may not be empty when bound: one dummy element without wind.
  wind_forces_.allocate((c.wind_enabled ? n : 1) * sizeof(glm::vec4));
  // The hash table is sized once; start[table_size] is the total, always n.
  table_size_ = c.table_size;
  cell_count_.allocate(table_size_ * sizeof(uint32_t));
  std::vector<uint32_t> start(table_size_ + 1, 0);
  start.back() = uint32_t(n);
  gl::upload_vector(cell_start_, start);
  cell_entries_.allocate(n * sizeof(uint32_t));
  sorted_positions_.allocate(n * sizeof(glm::vec4));
  normals_.allocate(n * sizeof(glm::vec4));
  no_offsets_.allocate(sizeof(glm::vec4));
}

void GpuState::upload_control(Constants<float>& c) {
  const layout::SubstepControl& block = c.control.block();
  if (substep_control_.size() == sizeof block) substep_control_.upload(0, sizeof block, &block);
  else substep_control_.allocate(sizeof block, &block, GL_DYNAMIC_DRAW);
  upload_colliders(c);
  upload_skins(c);
}

void GpuState::upload_colliders(Constants<float>& c) {
  // The fields never change during a run: uploaded when the constants bring another set.
  const std::vector<float>* sdf = c.sdf.get();
  if (sdf != sdf_source_ || sdf_.size() == 0) {
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &limit);
    if (sdf != nullptr && sdf->size() > size_t(limit))
      throw SceneError(fmt::format("the mesh colliders' fields have {} nodes in all, more than this GPU's texel buffers "
                                   "hold ({}): set a larger mesh.voxel_size",
                                   sdf->size(), limit));
    const std::vector<glm::vec4> texels = sdf != nullptr && !sdf->empty() ? sdf_cell_texels(*sdf, c.control.meshes)
                                                                         : std::vector<glm::vec4>(1, glm::vec4(0.f));
    gl::upload_vector(sdf_, texels, GL_STATIC_DRAW);
    sdf_view_.attach(sdf_, GL_RGBA32F);
    sdf_source_ = sdf;
    sdf_slopes_.clear();
  }
  // Each field's slope bound, measured once per set of fields (the contact list's bound, which
  // the reference does not read): kept in the colliders' own bound.x.
  if (sdf_slopes_.size() != c.control.meshes.size())
    sdf_slopes_ = sdf != nullptr ? sdf_slopes(*sdf, c.control.meshes) : std::vector<float>(c.control.meshes.size(), 1e30f);
  for (size_t k = 0; k < c.control.meshes.size(); ++k) c.control.meshes[k].bound.x = sdf_slopes_[k];
  // Control<float>'s arrays are the GPU's structs: uploaded as they are.
  if (upload_array(meshes_, c.control.meshes)) {
    meshes_view_.attach(meshes_, GL_RGBA32F);
    meshes_int_view_.attach(meshes_, GL_RGBA32I);
  }
  if (upload_array(spheres_, c.control.spheres)) spheres_view_.attach(spheres_, GL_RGBA32F);
  if (upload_array(planes_, c.control.planes)) planes_view_.attach(planes_, GL_RGBA32F);
}

void GpuState::upload_anchors(const Constants<float>& c) {
  std::vector<glm::vec4> anchors(c.anchors.begin(), c.anchors.end());
  if (anchors.empty()) anchors.resize(1);
  gl::upload_vector(anchors_, anchors, GL_STATIC_DRAW);
}

void GpuState::upload_rest_positions(const Constants<float>& c) {
  // Only the bounded contact and seams read them (one dummy texel otherwise: a view may not be
  // empty). w: the weld, exact in a float (particle indices are below 2^24).
  std::vector<glm::vec4> rest;
  for (size_t i = 0; i < c.rest.size(); ++i)
    rest.push_back({c.rest[i].x, c.rest[i].y, c.rest[i].z, c.welds ? float(c.weld[i]) : 0.f});
  if (rest.empty()) rest.resize(1);
  gl::upload_vector(rest_positions_, rest, GL_STATIC_DRAW);
  rest_positions_view_.attach(rest_positions_, GL_RGBA32F);
}

void GpuState::upload_materials(const Constants<float>& c) {
  std::vector<layout::MaterialTexels> materials;
  for (const MaterialC<float>& mat : c.materials)
    materials.push_back({glm::vec4(mat.ks, mat.ks_bending, mat.start_ks, 0.f),
                         glm::vec4(mat.keep_velocity, float(mat.enabled[0]), float(mat.enabled[1]), float(mat.enabled[2])),
                         glm::vec4(mat.moduli)});
  // z: the particle's attachment's collider (kind + 4 index, exact in a float), 0 for none.
  std::vector<glm::vec4> particles;
  for (size_t i = 0; i < c.mass.size(); ++i)
    particles.push_back({c.mass[i], float(model_.material[i]),
                         c.has_attachments() ? float(c.attach_collider[i]) : 0.f,
                         c.has_attachments() ? float(c.attach_vertex[i]) : 0.f});  // exact below 2^24
  gl::upload_vector(materials_, materials, GL_DYNAMIC_DRAW);
  gl::upload_vector(particles_, particles, GL_DYNAMIC_DRAW);
  materials_view_.attach(materials_, GL_RGBA32F);
  particles_view_.attach(particles_, GL_RGBA32F);
  // The attachments' anchors and stiffness (a live edit may change a stiffness).
  std::vector<glm::vec4> attach(c.attach.begin(), c.attach.end());
  if (attach.empty()) attach.resize(1);
  gl::upload_vector(attachments_, attach, GL_DYNAMIC_DRAW);
  attachments_view_.attach(attachments_, GL_RGBA32F);
}

uint64_t GpuState::stretch_settling_passes() const {
  if (stretch_control_.size() == 0) return 0;
  // The GPU's count is a uint: the host's 64 bits are for the CPU's statistic.
  return gl::download_vector<glm::uvec4>(stretch_control_, 0, 1)[0].y;
}

std::vector<uint32_t> GpuState::contact_list() const {
  if (contacts_.size() == 0) return {};
  const uint32_t count = gl::download_vector<layout::ContactListHeader>(contacts_, 0, 1)[0].dispatch_count.w;
  return gl::download_vector<uint32_t>(contacts_, sizeof(layout::ContactListHeader) / sizeof(uint32_t), count);
}

}  // namespace clothsim

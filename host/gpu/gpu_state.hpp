// The GPU's state (issue 42, item 4): every buffer the passes read and write, their texel views
// (compute/particle_views.glsl) and their bindings (layout.glsl), and the transfers of the hash.
// GpuSimulator owns one; GpuPasses (the programs, pass_table.hpp) runs on it. The uploads from
// the constants are gpu_state_uploads.cpp.
#pragma once

#include <memory>
#include <vector>

#include "backend.hpp"
#include "texture.hpp"
#include "../../compute/layout.glsl"

namespace clothsim {

struct GpuMultigrid;  // the multigrid solver's hierarchy and scratch buffers (gpu_multigrid.hpp)

class GpuState {
 public:
  // Checks the GPU's limits for the cloth (bad input, reported before any allocation).
  GpuState(const Scene& scene, const ClothModel& model);
  ~GpuState();

  // The buffers the renderer reads in place.
  const gl::Buffer& positions() const { return positions_; }
  const gl::Buffer& normals() const { return normals_; }
  void download_hash(SpatialHash& hash);  // count (cursors after fill), start, entries
  void upload_hash(const SpatialHash& hash);  // the same, for a stage checked on its own
  std::vector<glm::vec4> download_sorted_positions();
  std::vector<Vec4<float>> download_displacement() const;  // w zeroed: the GPU's scratch (predict.comp)
  // With stretch_passes_max above stretch_passes: the settling passes run so far (a read-back).
  uint64_t stretch_settling_passes() const;
  // The masses the last advance or predict listed for collide_objects (a read-back).
  std::vector<uint32_t> contact_list() const;
  // The skinned colliders' vertices and boxes, as Control::skinned holds them (a read-back).
  std::vector<Vec4<float>> download_skinned() const;

 private:
  friend class GpuPasses;     // runs its passes on these buffers
  friend class GpuSimulator;  // owns this state: transfers and edits

  // From the constants (gpu_state_uploads.cpp): the scratch and the hash table, once; the colliders
  // (the mesh colliders' slope bounds written into c.control.meshes), the moving pins' anchors, the rest
  // positions (the bounded contact) and the materials.
  void allocate_scratch(const Constants<float>& c);
  // The substep's control, c.control: its block (BINDING_SUBSTEP_CONTROL) and the colliders.
  void upload_control(Constants<float>& c);
  void upload_colliders(Constants<float>& c);
  void upload_anchors(const Constants<float>& c);  // one dummy element without pinned_motion
  void upload_rest_positions(const Constants<float>& c);  // Constants::rest, or one dummy texel
  void upload_materials(const Constants<float>& c);  // the materials, every particle's mass and material
  // The skinned colliders (gpu_skinning.cpp): the palette, every substep; their lists and bind
  // pose when the constants bring another set (one dummy texel each without).
  void upload_skins(const Constants<float>& c);

  // Binds every simulation buffer and view, on binding points and texture units no one else
  // uses (layout.glsl): at the start of every step, and for a pass called on its own (tests,
  // pass checks: another simulator in the same context may have bound its own since).
  void bind_all() const;
  void bind_multigrid() const;
  void attach_views();  // after any buffer is (re)allocated
  void swap_positions();  // the Jacobi/ping-pong output becomes the positions (rebinds the two)
  size_t buffer_bytes() const;  // every buffer here, the multigrid's included
  void upload_model();  // the cloth model's lists (springs, gather, triangles, corners)

  const ClothModel& model_;
  uint32_t table_size_ = 0;
  gl::Buffer positions_{"positions"}, displacement_{"displacement"}, forces_{"forces"}, normals_{"normals"};
  gl::Buffer springs_{"springs"}, spheres_{"spheres"}, planes_{"planes"}, step_params_{"step params"};
  gl::Buffer substep_control_{"substep control"};  // Control<float>'s block (layout::SubstepControl)
  gl::Buffer positions_out_{"positions out"}, cell_count_{"cell count"}, cell_start_{"cell start"};
  gl::Buffer cell_entries_{"cell entries"}, sorted_positions_{"sorted positions"};
  gl::Buffer wind_forces_{"wind forces"}, anchors_{"anchors"};
  gl::Buffer gather_start_{"gather start"}, gather_{"gather"}, particles_{"particles"}, materials_{"materials"};
  gl::Buffer corner_start_{"corner start"}, corner_triangles_{"corner triangles"}, triangles_{"triangles"};
  gl::Buffer rest_positions_{"rest positions"};
  gl::Buffer attachments_{"attachments"};  // Constants::attach (one texel of zeros without)
  // Mesh colliders: MeshCollider per mesh (rewritten per substep when one moves), and every
  // mesh's field, uploaded once (sdf_source_: the Constants::sdf it holds).
  gl::Buffer meshes_{"mesh colliders"}, sdf_{"mesh fields"};
  const std::vector<float>* sdf_source_ = nullptr;
  std::vector<float> sdf_slopes_;  // per mesh collider, its field's slope bound (sdf_slopes)
  // Read-only views of the buffers above (compute/particle_views.glsl).
  gl::BufferTexture positions_view_{"positions view"}, positions_out_view_{"positions out view"};
  gl::BufferTexture displacement_view_{"displacement view"}, springs_view_{"springs view"}, spheres_view_{"spheres view"};
  gl::BufferTexture gather_start_view_{"gather start view"}, gather_view_{"gather view"};
  gl::BufferTexture particles_view_{"particles view"}, materials_view_{"materials view"};
  gl::BufferTexture corner_start_view_{"corner start view"}, corner_triangles_view_{"corner triangles view"};
  gl::BufferTexture triangles_view_{"triangles view"};
  gl::BufferTexture planes_view_{"planes view"}, cell_start_view_{"cell start view"};
  gl::BufferTexture sorted_positions_view_{"sorted positions view"};
  gl::BufferTexture rest_positions_view_{"rest positions view"};
  gl::BufferTexture attachments_view_{"attachments view"};
  gl::BufferTexture meshes_view_{"mesh colliders view"}, sdf_view_{"mesh fields view"};
  // The same buffer as integers (TEXTURE_MESHES_INT): MeshCollider::dims, which the float view could flush.
  gl::BufferTexture meshes_int_view_{"mesh colliders integer view"};
  // The multigrid solver's buffers, made (or re-uploaded after an edit rebuilt the hierarchy)
  // before its first pass; none without the multigrid solver.
  std::unique_ptr<GpuMultigrid> multigrid_;
  // The settling passes' control (StretchControl, then a StretchDispatch per colour; made once,
  // so its count holds).
  gl::Buffer stretch_control_{"stretch control"};
  gl::Buffer contacts_{"contact list"};
  // Skinned mesh colliders (TEXTURE_SKINNED and its three inputs; layout.glsl).
  gl::Buffer skinned_{"skinned colliders"}, skin_indices_{"skin indices"}, skin_weights_{"skin weights"};
  gl::Buffer skin_palette_{"skin palette"};
  gl::Buffer nearest_{"nearest skinned triangles"};  // BINDING_NEAREST (compute/nearest.glsl's sections)
  size_t nearest_slots_ = 1;  // particles * skinned colliders, at least 1: the state's part of nearest_
  size_t nearest_words() const { return 5 * nearest_slots_ + 2; }
  const Vec4<float>* skin_source_ = nullptr;  // the Control::skinned its lists came with
  gl::BufferTexture skinned_view_{"skinned view"}, skin_indices_view_{"skin indices view"};
  gl::BufferTexture skin_weights_view_{"skin weights view"}, skin_palette_view_{"skin palette view"};  // ContactListHeader, then a uint per listed mass
  gl::Buffer no_offsets_{"no multigrid offsets"};  // one element, bound in their place without multigrid
};

}  // namespace clothsim

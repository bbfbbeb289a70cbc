// The model of docs/design.md §1 as compute passes over shader-storage buffers. The passes have
// the names of the CPU reference functions they mirror; step() is the same pass list.
// Positions stay on the GPU: the only read-backs are download() and snapshot(), on request.
// Split by concern: gpu_simulator.cpp (buffers, bindings, limits), gpu_step.cpp (the passes
// and the step), gpu_simulator_io.cpp (transfers), gpu_edits.cpp (live edits and the grab).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "backend.hpp"
#include "context.hpp"
#include "gpu_divergence.hpp"
#include "objects.hpp"
#include "prefix_scan.hpp"
#include "program.hpp"
#include "shader_features.hpp"
#include "texture.hpp"
#include "../../compute/layout.glsl"

namespace clothsim {

// What a pass's readers need after it wrote: storage-buffer reads and texel fetches (the
// passes read particle data through texel views, compute/particle_views.glsl). Shared by the
// passes of gpu_step.cpp, gpu_multigrid.cpp and gpu_stretch_limit.cpp.
inline constexpr GLbitfield kComputeReads = GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;

struct GpuMultigrid;  // the multigrid solver's programs and buffers (gpu_multigrid.cpp)
struct GpuSettlingPasses;  // enforce_stretch_limit's watched pass and its arm (gpu_stretch_limit.cpp)
struct GpuMultigridPass;

class GpuSimulator {
 public:
  // Needs a current GL 4.3 context. `compute_dir` holds the .comp files.
  GpuSimulator(const Scene& scene, const ClothModel& model, const std::filesystem::path& compute_dir);
  ~GpuSimulator();

  // The passes, one dispatch each (the length constraint: one per colour and iteration),
  // each named like its .comp file and its CPU twin in host/core/reference/reference.hpp. step() runs
  // advance, [collide_self], solve_length_constraints, with collide_objects fused into the
  // last per-particle pass before the constraints. accumulate_forces, integrate and
  // collide_objects on their own are kept only for the pass checks (pass_check.cpp).
  void compute_wind_forces();  // with wind: the aerodynamic force per particle, which advance adds
  void accumulate_forces();
  void integrate();
  void advance(bool then_collide_objects = false);  // accumulate_forces + integrate [+ collide_objects]
  void collide_self(bool then_collide_objects = false);  // the four hash stages below, then the response
  void collide_objects();
  void solve_length_constraint_colour(int colour);
  void solve_length_constraints();
  void compute_normals();
  // The xpbd solver's passes (docs/model.md): step() runs predict (+ collide_objects when
  // self-collision is off), [collide_self], solve_distance_constraints (or solve_multigrid),
  // then with simulation.stretch_passes enforce_stretch_limit (that many passes of
  // solve_length_constraints' shader over every colour).
  void predict(bool then_collide_objects = false);
  void solve_distance_constraint_colour(int colour);
  void solve_distance_constraints();
  void enforce_stretch_limit();
  // With stretch_passes_max above stretch_passes: the settling passes run so far (a read-back).
  uint64_t stretch_settling_passes() const;
  // The masses the last advance or predict listed for collide_objects, in the order listed (a
  // read-back; none where the step collides inline: self-collision on).
  std::vector<uint32_t> contact_list() const;
  // The multigrid solver's passes (docs/model.md; gpu_multigrid.cpp): step() runs predict,
  // [collide_self], then solve_multigrid: compute_residuals, the V-cycle (cycle_levels:
  // restrict_residuals per level down to the small ones, cycle_small_levels (their whole part
  // of the cycle in one dispatch), then prolong_corrections and smooth_corrections per colour
  // up), prolong_to_cloth, relax_vertices per colour. Levels count from 0, the first coarse one
  // (Hierarchy::levels); restrict_residuals, smooth_corrections and prolong_corrections take any
  // level (the pass checks run them on the small ones too).
  void compute_residuals();
  void restrict_residuals(int level);
  void smooth_corrections(int level, int colour);
  void cycle_small_levels();
  void prolong_corrections(int level);
  void prolong_to_cloth();
  void relax_vertices(int colour);
  void smooth_level(int level, int sweeps);  // `sweeps` sweeps of smooth_corrections, colour by colour
  void cycle_levels();  // the V-cycle: every pass between compute_residuals and prolong_to_cloth
  void solve_multigrid();
  int multigrid_dispatches() const;  // of one solve_multigrid
  // The multigrid scratch (State::residual, offset, coarse_rhs, coarse_corr), for the pass checks.
  void download_multigrid(State<float>& state);
  void upload_multigrid(const State<float>& state);

  // The stages of collide_self, named like their shaders and CPU twins (spatial_hash.hpp).
  void count_cells();
  void scan_cells();
  void fill_cells();
  void sort_cells();  // also writes the positions in cell order for the response
  // The last stage: the push-out over the hash the four stages built.
  void resolve_self_contacts(bool then_collide_objects = false);
  void download_hash(SpatialHash& hash);  // count (cursors after fill), start, entries
  void upload_hash(const SpatialHash& hash);  // the same, for a stage checked on its own
  std::vector<glm::vec4> download_sorted_positions();
  // The scanner, for tests of arbitrary lengths (up to the hash table size).
  PrefixScan& prefix_scan() { return scan_; }

  void step();        // one substep, the pass list of §1; then time() is one substep later
  // simulation_steps substeps, then normals, then the divergence guard's check. Throws
  // gl::GlError (gl::OutOfMemoryError for GL_OUT_OF_MEMORY) naming the GL error and the frame
  // when glGetError reports one, before the frame's passes (raised since the last frame by
  // another GL user) or after them (raised by a pass); debug builds also check after each pass.
  void step_frame();
  GpuDivergenceGuard& divergence() { return guard_; }

  // Simulated seconds at the start of the next substep. set_time also sets the moving parts
  // (colliders, pins, gusts) for the substep starting at t, as set_substep_time does on the
  // CPU (a checkpoint's time, or a pass check's).
  double time() const { return time_; }
  void set_time(double t);

  // Explicit transfers for export, validation and tests.
  void upload(const State<float>& state);  // pos, disp, and force and wind when present
  void download(State<float>& state);  // pos, disp, force, normal, and wind with wind
  std::vector<Vec4<float>> download_displacement() const;  // w zeroed: the GPU's scratch (predict.comp)

  // Live edits from the viewer. Parameters that keep the grid (stiffness, damping, density,
  // gravity, steps, thickness, ...) apply without a restart; a changed mass rescales every
  // inverse mass in place, a changed substep length every displacement (rescale_displacement:
  // the cloth keeps its velocity). The grid itself (size, points, orientation, pins) needs a new simulator.
  void set_parameters(const Scene& scene);
  // Holds particle i at `position` (at rest: displacement 0, inverse mass 0) until release_particle.
  void hold_particle(int i, const glm::vec3& position);
  void release_particle(int i);  // back to its own inverse mass (0 if it is pinned)
  void reset();                  // back to the initial state

  // The buffers the renderer reads in place.
  const gl::Buffer& positions() const { return positions_; }
  const gl::Buffer& normals() const { return normals_; }
  int dispatches_per_substep() const;
  GpuCounters counters() const;   // dispatches and barriers issued so far
  size_t memory_bytes() const;    // GPU buffer memory this simulator owns
  const Constants<float>& constants() const { return constants_; }
  const ShaderFeatures& shader_features() const { return features_; }  // what the passes are compiled for

 private:
  // Binds every simulation buffer and view, on binding points and texture units no one else
  // uses (layout.glsl): at the start of every step, and for a pass called on its own (tests,
  // pass checks: another simulator in the same context may have bound its own since).
  void bind_all() const;
  void bind_for_pass() const { if (!in_step_) bind_all(); }
  void attach_views();  // after any buffer is (re)allocated
  void swap_positions();  // the Jacobi/ping-pong output becomes the positions (rebinds the two)
  void upload_colliders();  // from constants_
  void upload_anchors();    // from constants_ (one dummy element without pinned_motion)
  void upload_rest_positions();  // Constants::rest (the bounded contact), or one dummy texel
  // The multigrid solver's programs and hierarchy buffers, made (or re-uploaded after an edit
  // rebuilt the hierarchy) before its first pass; nothing without the multigrid solver.
  void ensure_multigrid();
  void bind_multigrid() const;
  size_t multigrid_memory_bytes() const;
  void dispatch_range(GpuMultigridPass& pass, uint32_t first, uint32_t count);
  // xpbd's carried multipliers, one per spring (missing ones zero, one dummy without springs).
  void upload_multipliers(std::vector<Vec4<float>> multipliers);
  // Compiles every pass for `features` (the scene's collider code, shader_features.hpp): at
  // construction, and again when a live edit changes them.
  void load_passes(const ShaderFeatures& features);
  void upload_model();      // the cloth model's lists (springs, gather, triangles, corners, tethers)
  void upload_materials();  // from constants_: the materials and every particle's mass and material
  std::vector<float> inverse_masses() const;  // of every particle for the current densities
  void apply_substep_time();  // the moving parts of constants_ for the substep at time_, uploaded
  void barrier(GLbitfield bits);  // glMemoryBarrier, counted
  void dispatch(gl::Program& program);
  void dispatched(const gl::Program& program);  // counts a dispatch; debug builds check GL errors
  std::string pass_list() const;  // a substep's passes, for messages
  // One colour of a constraint pass (solve_length_constraints or solve_distance_constraints),
  // bindings already set: its springs' first index and count go to `where` (u_first, u_count).
  struct ColourUniforms { GLint first = -1, count = -1; };
  // `also`: more barrier bits for what reads after it (the contact list's indirect dispatch).
  void dispatch_colour(gl::Program& program, ColourUniforms where, int colour, GLbitfield also = 0);
  // `passes` sweeps of solve_length_constraints' shader over every enabled colour: the classic
  // constraint (constraint_iterations) and xpbd's enforce_stretch_limit (stretch_passes).
  void length_constraint_passes(int passes);
  // enforce_stretch_limit's watched passes, each armed on the GPU (gpu_stretch_limit.cpp).
  void settling_passes(int fixed);
  bool enabled_colour(int colour) const;  // has springs, of a type some cloth has on
  // The contact list (gpu_contacts.cpp, compute/contact_list.glsl): whether the step collides
  // through it (any collider: every kind has its exact early test), the cleared list bound for
  // advance, predict or a colour of a sweep, and collide_objects over what they listed.
  bool uses_contact_list() const;
  void start_contact_list();
  void collide_listed(bool friction = true);  // false: the sweeps' push-out (collide_objects' FRICTIONLESS)

  const ClothModel& model_;
  const std::filesystem::path dir_;
  Constants<float> constants_;
  std::vector<double> masses_;  // kg, for the current densities (particle_masses)
  double dt_;  // the substep length the displacements are per
  double time_ = 0;  // simulated seconds at the start of the next substep
  GpuCounters counters_;  // of a free particle, for the current density
  GLuint groups_ = 0;
  gl::Buffer positions_{"positions"}, displacement_{"displacement"}, forces_{"forces"}, normals_{"normals"};
  gl::Buffer springs_{"springs"}, spheres_{"spheres"}, planes_{"planes"}, step_params_{"step params"};
  gl::Buffer positions_out_{"positions out"}, cell_count_{"cell count"}, cell_start_{"cell start"};
  gl::Buffer cell_entries_{"cell entries"}, sorted_positions_{"sorted positions"}, tethers_{"tethers"};
  gl::Buffer wind_forces_{"wind forces"}, anchors_{"anchors"};
  gl::Buffer gather_start_{"gather start"}, gather_{"gather"}, particles_{"particles"}, materials_{"materials"};
  gl::Buffer corner_start_{"corner start"}, corner_triangles_{"corner triangles"}, triangles_{"triangles"};
  gl::Buffer rest_positions_{"rest positions"};
  gl::Buffer multipliers_{"multipliers"};  // xpbd: per spring, its direction and carried lambda
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
  gl::BufferTexture sorted_positions_view_{"sorted positions view"}, tethers_view_{"tethers view"};
  gl::BufferTexture rest_positions_view_{"rest positions view"};
  gl::BufferTexture multipliers_view_{"multipliers view"};
  gl::BufferTexture meshes_view_{"mesh colliders view"}, sdf_view_{"mesh fields view"};
  // The same buffer as integers (TEXTURE_MESHES_INT): MeshCollider::dims, which the float view could flush.
  gl::BufferTexture meshes_int_view_{"mesh colliders integer view"};
  uint32_t table_size_ = 0;
  bool in_step_ = false;
  bool in_frame_ = false;  // within step_frame's substeps
  int substep_ = 0;        // of the frame, while in_frame_
  ShaderFeatures features_;  // what the passes below were compiled for
  gl::Program compute_wind_forces_, accumulate_forces_, integrate_, advance_, collide_objects_, solve_length_constraints_, compute_normals_;
  gl::Program count_cells_, fill_cells_, sort_cells_, resolve_self_contacts_;
  gl::Program predict_, solve_distance_constraints_;
  // collide_objects over the contact list (compiled with LISTED), and without friction.
  gl::Program collide_listed_, collide_listed_frictionless_;
  // Uniforms set before a dispatch, looked up once.
  GLint advance_collide_objects_ = -1, resolve_collide_objects_ = -1, predict_collide_objects_ = -1;
  ColourUniforms length_colour_, distance_colour_;
  PrefixScan scan_;
  GpuDivergenceGuard guard_;
  std::unique_ptr<GpuMultigrid> multigrid_;
  // The settling passes' programs (made on first use, again after load_passes) and their control
  // buffer (StretchControl, then a StretchDispatch per colour; made once, so its count holds).
  std::unique_ptr<GpuSettlingPasses> settling_;
  gl::Buffer stretch_control_{"stretch control"};
  gl::Buffer contacts_{"contact list"};  // ContactListHeader, then a uint per listed mass
  gl::Buffer no_offsets_{"no multigrid offsets"};  // one element, bound in their place without multigrid
};

// The GPU simulator as a Backend: owns the headless context it runs in.
class GpuBackend final : public Backend {
 public:
  GpuBackend(std::unique_ptr<gl::GlContext> context, const Scene& scene, const ClothModel& model,
             const std::filesystem::path& compute_dir);
  void step_frame() override { sim_->step_frame(); }
  ClothSnapshot snapshot() override;
  std::vector<FrameCheck> take_checks(bool all) override { return sim_->divergence().take(all); }
  ClothSnapshot last_good(int* frame) override {
    return snapshot_of_positions(model_, sim_->divergence().last_good(frame));
  }
  std::string name() const override;
  SavedState save_state() override;
  void load_state(const SavedState& saved) override;
  int scalar_bytes() const override { return int(sizeof(float)); }
  double time() const override { return sim_->time(); }
  uint64_t stretch_settling_passes() const override { return sim_->stretch_settling_passes(); }
  GpuSimulator& simulator() { return *sim_; }
  const GpuSimulator& simulator() const { return *sim_; }

 private:
  std::unique_ptr<gl::GlContext> context_;
  const ClothModel& model_;
  std::unique_ptr<GpuSimulator> sim_;
};

// Where the GLSL files are: $CLOTHSIM_ROOT, then the directory above the executable
// (build/ in a source tree), then the source tree the binary was built from.
std::filesystem::path find_project_root(const std::filesystem::path& hint = {});

}  // namespace clothsim

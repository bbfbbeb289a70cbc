#include "reference/reference.hpp"

#include <algorithm>
#include <numeric>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <fmt/format.h>

#include "colliders/mesh_collider.hpp"
#include "scene/motion.hpp"
#include "reference/reference_detail.hpp"
#include "reference/reference_skinning.hpp"

namespace clothsim {

bool Timeline::moves() const {
  for (auto& k : spheres) if (k) return true;
  for (auto& k : planes) if (k) return true;
  for (auto& k : meshes) if (k) return true;
  return !skins.empty() || pins.has_value() || gust_period > 0 || sewing_speed > 0;
}

namespace {

// xyz of a collider's vec4 from a point in double, rounded once; w kept.
template <class R> void set_xyz(Vec4<R>& v, const glm::dvec3& p) { v = Vec4<R>(Vec3<R>(p), v.w); }

template <class R> void make_wind(const Scene& scene, Constants<R>& c) {
  if (!scene.wind) return;
  const WindParams& w = *scene.wind;
  c.wind_enabled = 1;
  c.wind_velocity = Vec3<R>(w.velocity);
  c.wind_drag = R(-w.air_density * w.drag_coefficient / 12.0);
  c.wind_lift = R(-w.air_density * w.lift_coefficient / 12.0);
  c.wind_inv_3dt = R(1.0 / (3.0 * scene.dt()));
  const double speed = std::sqrt(w.velocity.x * w.velocity.x + w.velocity.y * w.velocity.y + w.velocity.z * w.velocity.z);
  // Gusts need a direction to travel along: none in still air.
  if (w.gust && w.gust->strength > 0 && speed > 0) {
    c.gust_enabled = 1;
    c.gust_velocity = Vec3<R>(w.velocity * w.gust->strength);
    c.wind_direction = Vec3<R>(w.velocity / speed);
    c.gust_inv_length3 = R(1.0 / (3.0 * w.gust->length));
    c.timeline.gust_period = w.gust->period;
  }
}

template <class R> void make_timeline(const Scene& scene, const ClothModel& model, Constants<R>& c) {
  Timeline& tl = c.timeline;
  tl.dt = scene.dt();
  for (auto& s : scene.spheres) tl.spheres.push_back(s.motion ? std::optional(s.motion->keyframes) : std::nullopt);
  for (auto& p : scene.planes) tl.planes.push_back(p.motion ? std::optional(p.motion->keyframes) : std::nullopt);
  for (auto& m : scene.meshes) tl.meshes.push_back(m.motion ? std::optional(m.motion->keyframes) : std::nullopt);
  // pinned_motion of the first cloth moves the pins of every cloth (one offset for all).
  if (scene.cloth.pinned_motion) {
    tl.pins = scene.cloth.pinned_motion->keyframes;
    for (int i = 0; i < model.count(); ++i)
      c.anchors.push_back(Vec4<R>(Vec3<R>(model.initial[i]), model.pinned[i] ? R(1) : R(0)));
  }
  if (model.has_seams()) tl.sewing_speed = scene.simulation.sewing_speed;
  // Where the colliders are at t = 0, at rest: set_substep_time takes over from the first substep.
  for (size_t k = 0; k < tl.spheres.size(); ++k)
    if (tl.spheres[k]) set_xyz(c.control.spheres[k].origin_radius, interpolate(*tl.spheres[k], 0.0));
  for (size_t k = 0; k < tl.planes.size(); ++k)
    if (tl.planes[k]) set_xyz(c.control.planes[k].point, interpolate(*tl.planes[k], 0.0));
  for (size_t k = 0; k < tl.meshes.size(); ++k)
    if (tl.meshes[k]) set_mesh_origin(c.control.meshes[k], Vec3<R>(interpolate(*tl.meshes[k], 0.0)));
}

// cloth.attachments: which particles follow which collider, and by how much (Constants::attach).
template <class R> void make_attachments(const Scene& scene, const ClothModel& model, Constants<R>& c) {
  const auto cloths = scene.cloths();
  bool any = false;
  for (const ClothParams* p : cloths) any = any || !p->attachments.empty();
  if (!any) return;
  c.attach.assign(size_t(model.count()), Vec4<R>(0));
  c.attach_collider.assign(size_t(model.count()), 0u);
  c.attach_vertex.assign(size_t(model.count()), 0u);
  const bool array = cloths.size() > 1;
  for (size_t part = 0; part < cloths.size(); ++part) {
    const ClothPart& cp = model.parts[part];
    for (size_t k = 0; k < cloths[part]->attachments.size(); ++k) {
      const AttachmentParams& a = cloths[part]->attachments[k];
      const ColliderRef ref = *find_collider(scene, a.collider);  // the loader checked it
      const glm::dvec3 origin = collider_origin(scene, ref, 0.0);
      const bool skinned = ref.kind == 3 && c.control.meshes[ref.index].skin.y > 0;
      auto attach = [&](uint32_t i) {
        if (model.pinned[i]) return;  // a pin stays a pin
        // A skinned collider: the vertex follows its nearest skinned vertex at t = 0 (a bone's
        // surface), not the collider's origin.
        const uint32_t v = skinned ? nearest_skinned_vertex(c, ref.index, model.initial[i]) : 0u;
        const glm::dvec3 from = skinned ? glm::dvec3(Vec3<R>(c.control.skinned[v])) : origin;
        c.attach[i] = Vec4<R>(Vec3<R>(model.initial[i] - from), R(a.stiffness));
        c.attach_collider[i] = uint32_t(ref.kind) + 4u * uint32_t(ref.index);
        if (skinned) c.attach_vertex[i] = v;
      };
      const std::string key = fmt::format("{}.attachments[{}]", array ? fmt::format("cloth[{}]", part) : "cloth", k);
      for (size_t v = 0; v < a.vertices.size(); ++v) {
        if (a.vertices[v] < 0 || uint32_t(a.vertices[v]) >= cp.count)
          throw SceneError(fmt::format("{}: {}.vertices[{}]: vertex {} is out of range: the cloth has {} vertices "
                                       "(0 to {})",
                                       scene.source, key, v, a.vertices[v], cp.count, cp.count - 1));
        attach(cp.first + uint32_t(a.vertices[v]));
      }
      if (a.box)
        for (uint32_t i = cp.first; i < cp.first + cp.count; ++i)
          if (a.box->contains(model.initial[i])) attach(i);
    }
  }
}

// Each mesh collider's field, appended to one array the backends share (GPU: one buffer).
template <class R> void make_meshes(const Scene& scene, Constants<R>& c) {
  if (scene.meshes.empty()) return;
  std::vector<std::shared_ptr<const ColliderMesh>> loaded;
  uint32_t offset = 0;
  for (size_t k = 0; k < scene.meshes.size(); ++k) {
    const std::shared_ptr<const ColliderMesh> mesh = load_collider_mesh(scene, k);
    loaded.push_back(mesh);
    c.control.meshes.push_back(make_mesh_collider<R>(scene.meshes[k], mesh->sdf, offset));
    c.timeline.mesh_origins.push_back(scene.meshes[k].origin);
    offset += uint32_t(mesh->sdf.values.size());
  }
  c.sdf = concatenated_fields(loaded);
  make_skins(scene, loaded, c);
}

}  // namespace

template <class R> void set_substep_time(Constants<R>& c, double t) {
  const Timeline& tl = c.timeline;
  Control<R>& now = c.control;
  const double t1 = t + tl.dt;
  now.time = t1;
  // The motion is rounded once, from double.
  auto motion = [&](const Keyframes& k, const glm::dvec3& at, R w) { return Vec4<R>(Vec3<R>(at - interpolate(k, t)), w); };
  for (size_t k = 0; k < tl.spheres.size(); ++k)
    if (tl.spheres[k]) {
      const glm::dvec3 at = interpolate(*tl.spheres[k], t1);
      set_xyz(now.spheres[k].origin_radius, at);
      now.spheres[k].motion = motion(*tl.spheres[k], at, now.spheres[k].motion.w);
    }
  for (size_t k = 0; k < tl.planes.size(); ++k)
    if (tl.planes[k]) {
      const glm::dvec3 at = interpolate(*tl.planes[k], t1);
      set_xyz(now.planes[k].point, at);
      now.planes[k].motion = motion(*tl.planes[k], at, now.planes[k].motion.w);
    }
  for (size_t k = 0; k < tl.meshes.size(); ++k)
    if (tl.meshes[k]) {
      const glm::dvec3 at = interpolate(*tl.meshes[k], t1);
      set_mesh_origin(now.meshes[k], Vec3<R>(at));
      now.meshes[k].motion = motion(*tl.meshes[k], at, now.meshes[k].motion.w);
    }
  if (!tl.skins.empty()) set_skin_palette(c, t, t1);
  if (tl.pins) now.pin_offset = Vec3<R>(interpolate(*tl.pins, t1));
  if (tl.gust_period > 0) now.gust_phase = R(gust_phase(t, tl.gust_period));
  if (tl.sewing_speed > 0) now.seam_shrink = R(tl.sewing_speed * t1);
}

int stretch_passes_for(const Scene& scene, const ClothModel& model) {
  const SimulationParams& sp = scene.simulation;
  if (sp.stretch_passes >= 0) return sp.stretch_passes;
  if (sp.solver != Solver::Fabric) return 0;
  const std::vector<const ClothParams*> cloths = scene.cloths();
  for (size_t k = 0; k < cloths.size() && k < model.parts.size(); ++k) {
    const ClothPart& part = model.parts[k];
    if (part.count == 0) continue;
    glm::dvec3 lo = model.initial[part.first], hi = lo;
    for (uint32_t i = part.first; i < part.first + part.count; ++i) {
      lo = glm::min(lo, model.initial[i]);
      hi = glm::max(hi, model.initial[i]);
    }
    const glm::dvec3 size = hi - lo;
    const double extent = std::max({size.x, size.y, size.z});
    // The stretch of a strip hanging from its top under its own weight, its springs alone
    // holding it (an upper bound: the shearing and bending springs carry some of it).
    const double sag_stretch = cloths[k]->areal_density() * glm::length(sp.gravity) * extent / cloths[k]->spring_ks();
    if (!(sag_stretch <= 0.5 * sp.max_stretch)) return kAutoStretchPasses;  // ks 0 too
  }
  // Seams: one pass, whose seam colours weld the sewn pairs (docs/model.md, "Sewing"); the
  // sweep's own limit moves one end at a time, which would act on a pair as a force.
  return model.has_seams() ? 1 : 0;
}

template <class R>
Constants<R> make_constants(const Scene& scene, const ClothModel& model, std::shared_ptr<const Hierarchy> reuse) {
  const ClothParams& cp = scene.cloth;
  const SimulationParams& sp = scene.simulation;
  Constants<R> c{};
  const double dt = scene.dt();
  // Derived values are formed in double and rounded once, identically for the GPU upload.
  c.gravity = Vec3<R>(sp.gravity);
  c.dt2 = R(dt * dt);
  c.stretch_limit = R(1.0 + sp.max_stretch);
  // Cloths of different thickness keep the thickest one's distance from each other and themselves.
  double thickness = cp.thickness;
  for (const ClothParams* k : scene.cloths()) thickness = std::max(thickness, k->thickness);
  c.contact_distance = R(2.0 * thickness);
  c.inv_cell = R(1.0 / (2.0 * thickness));
  check_self_collision_cost(scene, model);  // a thickness many times the spacing: refused
  c.steps = R(sp.simulation_steps);
  for (const ClothParams* k : scene.cloths()) {
    MaterialC<R> mat{};
    mat.ks = R(k->spring_ks());
    mat.ks_bending = R(0.2 * k->spring_ks());
    mat.start_ks = R(k->material ? kMaterialStartStiffness : k->ks);
    mat.keep_velocity = R(1.0 - k->damping / 100.0);
    // A material's triangles and stencils replace the springs (docs/materials.md); its
    // structural springs stay on for max_stretch's passes alone (enforce_stretch_limit): its
    // particles' gathers hold none, so they add no force.
    mat.enabled[0] = k->enable_structural;
    mat.enabled[1] = k->enable_shearing && !k->material;
    mat.enabled[2] = k->enable_bending && !k->material;
    if (k->material) mat.moduli = Vec4<R>(R(k->material->stretch[0]), R(k->material->stretch[1]), R(k->material->compression), R(k->material->shear));
    mat.enabled[3] = true;  // seams
    c.materials.push_back(mat);
  }
  // From the scene, so a live density edit takes effect.
  for (double m : particle_masses(scene, model)) c.mass.push_back(R(m));
  for (uint32_t i = 0; i < uint32_t(model.count()); ++i) {
    c.particle_ks.push_back(c.materials[model.material[i]].ks);
    c.start_ks.push_back(c.materials[model.material[i]].start_ks);
  }
  const bool fabric = sp.solver == Solver::Fabric;
  c.multigrid = fabric;
  // Where the multigrid solve starts (shared/integration.glsl, solve_start_offset): multigrid less
  // the external forces' move, fabric where the last substep's move says (scaled down where a
  // mass is stiffer for its inertia than kAdaptiveStartRho).
  c.adaptive_rho = R(fabric ? kAdaptiveStartRho : 0.0);
  c.sweep_friction = fabric ? 1u : 0u;  // relax_vertices' push-out
  c.folded_chord = R(kFoldedChordFabric);
  c.folded_chord_stiff = R(kFoldedChordMultigrid);
  c.inv_dt2 = R(1.0 / (dt * dt));
  c.max_move = R(sp.max_speed * dt);  // 0: no speed clamp
  if (c.multigrid) {
    std::vector<double> ks;
    for (const ClothParams* k : scene.cloths()) ks.push_back(k->spring_ks());
    c.hierarchy = reuse && reuse->ks == ks ? std::move(reuse) : std::make_shared<const Hierarchy>(build_hierarchy(model, ks));
  }
  c.iterations = sp.constraint_iterations;
  c.stretch_passes = fabric ? stretch_passes_for(scene, model) : 0;
  const bool auto_settling = sp.stretch_passes < 0 && sp.stretch_passes_max < 0 && c.stretch_passes == kAutoStretchPasses;
  c.stretch_passes_max = fabric ? std::max(auto_settling ? kAutoStretchPassesMax : sp.stretch_passes_max, c.stretch_passes) : 0;
  c.self_collision = sp.self_collision;
  c.bounded_contact = fabric && c.self_collision;
  c.coulomb_friction = fabric;
  if (c.bounded_contact) {
    // A mass moves at most a quarter of the contact distance per substep: two masses closing
    // on each other cover at most half of it, so a mass of one layer is seen by the other's
    // masses before it can reach the gap between them (docs/model.md).
    c.max_step = R(kMaxStepFraction * 2.0 * thickness);
  }
  c.weld = model.weld;
  c.welds = model.has_seams() ? 1u : 0u;
  if (c.bounded_contact || c.welds)  // the GPU packs both in one texel per particle
    for (const glm::dvec3& p : model.initial) c.rest.push_back(Vec3<R>(p));
  c.count = uint32_t(model.count());
  c.table_size = hash_table_size(uint32_t(model.count()));
  for (auto& s : scene.spheres)
    c.control.spheres.push_back({Vec4<R>(Vec3<R>(s.origin), R(s.radius)), Vec4<R>(R(1.0 - s.friction), R(s.friction), 0, 0), Vec4<R>(0)});
  for (auto& p : scene.planes)
    c.control.planes.push_back({Vec4<R>(Vec3<R>(p.point), R(1)), Vec4<R>(Vec3<R>(p.normal), R(1.0 - p.friction)),
                        Vec4<R>(Vec3<R>(0), R(p.friction))});
  make_meshes(scene, c);
  make_wind(scene, c);
  make_timeline(scene, model, c);
  if (!c.timeline.skins.empty()) {  // the skinned colliders at t = 0, still (the attachments read them)
    set_skin_palette(c, 0.0, 0.0);
    skin_colliders(c.control, c);
    fit_collider_boxes(c.control, c);
  }
  make_attachments(scene, model, c);
  // Each plane's front: the side the cloth's rest centre is on, where the plane is at t = 0.
  glm::dvec3 centre(0.0);
  for (auto& p : model.initial) centre += p;
  centre /= double(std::max(1, model.count()));
  for (size_t k = 0; k < c.control.planes.size(); ++k) {
    const glm::dvec3 at = keyed_at(c.timeline.planes[k], scene.planes[k].point, 0.0);
    c.control.planes[k].point.w = glm::dot(centre - at, scene.planes[k].normal) < 0 ? R(-1) : R(1);  // its front
  }
  c.sphere_count = uint32_t(c.control.spheres.size());
  c.plane_count = uint32_t(c.control.planes.size());
  c.mesh_count = uint32_t(c.control.meshes.size());
  c.pins_moving = c.moving_pins();
  return c;
}

template <class R> State<R> initial_state(const ClothModel& m) {
  State<R> s;
  const int n = m.count();
  s.pos.resize(n);
  for (int i = 0; i < n; ++i)
    s.pos[i] = Vec4<R>(Vec3<R>(m.initial[i]), m.pinned[i] ? R(0) : R(1.0 / m.mass[i]));
  s.disp.assign(n, Vec4<R>(0));  // at rest
  s.force.assign(n, Vec4<R>(0));
  s.normal.assign(n, Vec4<R>(0));
  s.pos_out = s.pos;
  s.hash = make_spatial_hash(uint32_t(n));
  return s;
}

#define CLOTHSIM_INSTANTIATE(R) \
  template Constants<R> make_constants<R>(const Scene&, const ClothModel&, std::shared_ptr<const Hierarchy>); \
  template State<R> initial_state<R>(const ClothModel&); \
  template void set_substep_time<R>(Constants<R>&, double);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

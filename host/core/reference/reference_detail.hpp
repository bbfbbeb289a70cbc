// Shared by the reference's pass files, not part of its interface.
#pragma once

#include "reference/reference.hpp"
#include "colliders/sdf.hpp"
#include "../../../compute/shared/collisions.glsl"
#include "../../../compute/shared/springs.glsl"

namespace clothsim {

// One particle against every sphere, then every plane (reference_collisions.cpp). With
// `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out against a collider that moved.
// `slots`, `search`: the mass's nearest skinned triangles, found anew (the substep's first
// collision) or reused (reference_skinning.hpp, mesh_at). `still_only`: fabric's sweep, whose
// friction holds only against colliders that did not move this substep (shared::takes_friction;
// g_friction_still_only in compute/collide_objects.glsl).
template <class R> void collide_particle(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, bool friction,
                                         uint32_t* slots = nullptr, bool search = false, bool still_only = false);
// relax_vertices' self-contacts under fabric (reference_collisions.cpp, docs/model.md "Self-contact
// in the sweep"): mass i's penalty springs (SELF_CONTACT_STIFFNESS times its ks) into f and hess;
// start_i: where i began the substep (x - d).
template <class R>
void add_self_contacts(const Constants<R>& c, const State<R>& s, uint32_t i, const Vec3<R>& x, const Vec3<R>& start_i,
                       Vec3<R>& f, shared::Sym3<R>& hess);
// A mass deeper than 0.1 mm inside a sphere, or behind a plane's front, goes back to the
// surface (a plane's: its surface offset on the front), without friction; otherwise nothing.
template <class R> void keep_out_of_colliders(const Constants<R>& c, Vec3<R>& x, Vec3<R>& d, uint32_t* slots = nullptr);

// The colliders' formulas and contact responses, written once for both backends.
using shared::blend_to;
using shared::blend_to_moving;
using shared::coulomb_respond;
using shared::keep_in_front_of_plane;
using shared::keep_out_of_sphere;
using shared::moving_sphere_push;
using shared::passed_through_sphere;
using shared::plane_side;
using shared::plane_sides;
using shared::respond_to_contact;
using shared::respond_to_plane;
using shared::respond_to_sphere;
using shared::static_sphere_push;
using shared::stays_in_front;

// A mass against one mesh collider's field (reference_mesh_collisions.cpp): pushed out to
// `thickness` along the field's gradient, with the collider's friction (none when `friction` is
// false); and the same push without friction for a mass deeper than 0.1 mm (keep_out_of_mesh).
template <class R> void collide_with_mesh(const Constants<R>& c, const MeshColliderT<R>& m, bool friction, Vec3<R>& x, Vec3<R>& d);
template <class R> void keep_out_of_mesh(const Constants<R>& c, const MeshColliderT<R>& m, Vec3<R>& x, Vec3<R>& d);
// The field of `m` at local point p (sdf: Constants::sdf): false outside its grid.
template <class R> bool sample_mesh_field(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& p, R& phi, Vec3<R>& grad);
// World point x in the collider's own frame (its field's and its surface's).
template <class R> Vec3<R> mesh_local_point(const MeshColliderT<R>& m, const Vec3<R>& x);
// The same at world point x (where m.origin puts the mesh).
template <class R> bool sample_mesh_at(const MeshColliderT<R>& m, const float* sdf, const Vec3<R>& x, R& phi, Vec3<R>& grad);
// A mesh collider's constants from its scene entry and its field, placed at p.origin; offset:
// its first node in the array the field is read from (Constants::sdf).
template <class R> MeshColliderT<R> make_mesh_collider(const MeshColliderParams& p, const SdfGrid& g, uint32_t offset);

// Skinned mesh colliders (reference_skinning.cpp): their lists, clusters and timelines from the
// loaded meshes (after their MeshColliders are made), and the palette at times start and end
// (Control::palette's two halves).
struct ColliderMesh;
template <class R>
void make_skins(const Scene& scene, const std::vector<std::shared_ptr<const ColliderMesh>>& loaded, Constants<R>& c);
template <class R> void set_skin_palette(Constants<R>& c, double start, double end);
// The skinned vertex of mesh collider `mesh` nearest p where skin_colliders last put them (the
// least distance, then index): what an attachment to it follows.
template <class R> uint32_t nearest_skinned_vertex(const Constants<R>& c, size_t mesh, const glm::dvec3& p);


}  // namespace clothsim

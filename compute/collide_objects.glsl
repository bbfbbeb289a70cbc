// One particle against every sphere in file order, then every plane (docs/design.md §1.4), then
// every mesh collider (docs/model.md); the formulas are compute/shared/collisions.glsl's, the
// loops and the reads of the colliders' parameters this file's. x is its position, d its
// displacement of this substep (x_prev = x - d); both change. Shared by collide_objects.comp and the passes it is
// fused into (advance, resolve_self_contacts).
#ifndef CLOTHSIM_COLLIDE_OBJECTS_GLSL
#define CLOTHSIM_COLLIDE_OBJECTS_GLSL

#include "particle_views.glsl"
#include "features.glsl"

#include "shared/collisions.glsl"
// Set by fabric's sweep (relax_vertices, and the push-out after its stretch passes): friction
// only against colliders that did not move this substep (takes_friction).
bool g_friction_still_only = false;
#include "collide_meshes.glsl"

// With `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out that xpbd's constraint pass applies after each correction (docs/model.md); applying
// it twice changes nothing.
void collide_with_objects_friction(inout vec3 x, inout vec3 d, bool friction) {
  for (int s = 0; s < sphere_count(); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    vec4 keep_mu = texelFetch(spheres_view, SPHERE_TEXELS * s + 1);
    vec3 m = collider_motion(texelFetch(spheres_view, SPHERE_TEXELS * s + 2).xyz);
    bool held = takes_friction(friction, g_friction_still_only, m);
    float keep = held ? keep_mu.x : 1.0;
    float r = origin_radius.w;
    vec3 e = x - origin_radius.xyz;
    float dist = length3(e);
    // One push for the three cases below, then one response: llvmpipe runs every branch, so
    // a response in each would cost three times over.
    precise vec3 t_minus_x;
    vec3 frame_motion = m;  // the sphere's motion in the response (zero for a static one)
    if (dist > r) {
      // Outside at the end: caught if it went through the sphere during the substep.
      if (!passed_through_sphere(e, dist, r, d - m, t_minus_x)) continue;
    } else if (nonzero3(m)) {
      t_minus_x = moving_sphere_push(e, dist, r, d, m);
    } else {
      frame_motion = vec3(0.0);
      t_minus_x = static_sphere_push(e, dist, r, d);
    }
    respond_to_sphere(held && COULOMB_FRICTION, origin_radius.xyz, keep, keep_mu.y, frame_motion, t_minus_x, x,
                      d);
    keep_out_of_sphere(origin_radius.xyz, r, x, d);
  }
  for (int k = 0; k < plane_count(); ++k) {
    vec4 point_front = texelFetch(planes_view, PLANE_TEXELS * k);
    vec4 normal_keep = texelFetch(planes_view, PLANE_TEXELS * k + 1);
    vec4 motion_mu = texelFetch(planes_view, PLANE_TEXELS * k + 2);
    vec3 m = collider_motion(motion_mu.xyz);
    vec3 n = normal_keep.xyz;
    float front = point_front.w;
    bool coulomb = friction && COULOMB_FRICTION;  // the contact test's (resting contact)
    bool held = takes_friction(friction, g_friction_still_only, m);
    if (!held) normal_keep.w = 1.0;
    // The classic crossing test (in the plane's frame, x_prev - p_prev = (x - p) - (d - m), so a
    // sweep is seen at any speed), and a mass found behind the front at both ends of the
    // substep is lifted to the front (docs/model.md); with Coulomb friction a mass within the
    // surface offset in front is in contact too (resting contact).
    float dist, dist_prev;
    bool crossed = plane_sides(x, d, point_front.xyz, n, m, dist, dist_prev);
    if (!crossed && stays_in_front(dist, front, coulomb)) continue;
    float side = plane_side(crossed, dist_prev, front);
    respond_to_plane(held && COULOMB_FRICTION, n, front, normal_keep.w, motion_mu.w, m, dist, side, x, d);
    // The blend of a mass found behind starts from x_prev, behind too: it can end behind.
    if (side == front) keep_in_front_of_plane(point_front.xyz, n, front, x, d);
  }
  for (int k = 0; k < mesh_count(); ++k) collide_with_mesh(k, friction, x, d);
}

void collide_with_objects(inout vec3 x, inout vec3 d) { collide_with_objects_friction(x, d, true); }

// Whether one collider's response could change a mass at x that moved by d (its motion m):
// false only where it would leave the mass at its first test (a path that stays outside a
// sphere, a mass that did not cross a plane and ends in front; for a mesh, mesh_leaves_alone),
// computed by the same functions on the same values as the response (or, for a mesh after
// predict, a bound of them: mesh_leaves_alone_after).
bool sphere_may_move(vec4 origin_radius, vec3 m, vec3 x, vec3 d) {
  float dist = length3(x - origin_radius.xyz);
  return !(dist > origin_radius.w) || !path_stays_outside(dist, origin_radius.w, d - m);
}
bool plane_may_move(vec4 point_front, vec3 n, vec3 m, vec3 x, vec3 d, bool friction) {
  float dist, dist_prev;
  return plane_sides(x, d, point_front.xyz, n, m, dist, dist_prev) ||
         !stays_in_front(dist, point_front.w, friction && COULOMB_FRICTION);
}
// Whether a sphere or a plane could change a mass at x that moved by d: true where one may move
// it (sphere_may_move, plane_may_move).
bool analytic_may_move(vec3 x, vec3 d, bool friction) {
  bool may = false;
  for (int s = 0; s < sphere_count(); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    vec3 m = collider_motion(texelFetch(spheres_view, SPHERE_TEXELS * s + 2).xyz);
    may = may || sphere_may_move(origin_radius, m, x, d);
  }
  for (int k = 0; k < plane_count(); ++k) {
    vec4 point_front = texelFetch(planes_view, PLANE_TEXELS * k);
    vec3 n = texelFetch(planes_view, PLANE_TEXELS * k + 1).xyz;
    vec3 m = collider_motion(texelFetch(planes_view, PLANE_TEXELS * k + 2).xyz);
    may = may || plane_may_move(point_front, n, m, x, d, friction);
  }
  return may;
}

// Whether every mesh collider leaves a mass at x, moved by d, alone (mesh_leaves_alone, a field
// sample each), and the mass's clearance bound for the passes after predict: the least over
// the meshes, 0 where it is not positive or there is no mesh (0: no bound).
bool meshes_leave_alone(vec3 x, vec3 d, out float clearance) {
  bool alone = true;
  float least = 3.0e38;
  for (int k = 0; k < mesh_count(); ++k) {
    MeshField field = mesh_field(k);
    bool this_one = mesh_leaves_alone(field, x, d, least);  // (not inside &&: every mesh bounds `least`)
    alone = alone && this_one;
  }
  clearance = mesh_count() > 0 && least > 0.0 ? least : 0.0;
  return alone;
}

// Whether collide_with_objects_friction could change a mass at x that moved by d (advance,
// predict: their own positions): true where some collider may move it, so the decision is the
// one the full response makes and skipping a mass is exact. Also its clearance bound
// (meshes_leave_alone).
bool may_collide(vec3 x, vec3 d, bool friction, out float clearance) {
  bool meshes_alone = meshes_leave_alone(x, d, clearance);
  return analytic_may_move(x, d, friction) || !meshes_alone;
}

// The same for mass i in fabric's sweep, with the clearance predict kept (`clearance`): the
// meshes decide without a field sample (mesh_leaves_alone_after), so a mass near a mesh may be
// pushed out inline and then left alone by the response (relax_vertices' push_out).
bool may_collide_after(int i, vec3 x, vec3 d, float clearance, bool friction) {
  bool may = analytic_may_move(x, d, friction);
  for (int k = 0; k < mesh_count(); ++k) may = may || !mesh_leaves_alone_after(mesh_field(k), x, d, clearance, i);
  return may;
}

// A mass deeper than 0.1 mm inside a sphere, or behind a plane's front, goes back to the
// surface without friction.
void keep_out_of_colliders(inout vec3 x, inout vec3 d) {
  for (int s = 0; s < sphere_count(); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    keep_out_of_sphere(origin_radius.xyz, origin_radius.w, x, d);
  }
  for (int k = 0; k < plane_count(); ++k) {
    vec4 point_front = texelFetch(planes_view, PLANE_TEXELS * k);
    vec3 n = texelFetch(planes_view, PLANE_TEXELS * k + 1).xyz;
    keep_in_front_of_plane(point_front.xyz, n, point_front.w, x, d);
  }
  for (int k = 0; k < mesh_count(); ++k) {
    MeshField m = mesh_field(k);
    if (mesh_at(m, x, d)) keep_out_of_mesh(m, x, d);
  }
}

#endif

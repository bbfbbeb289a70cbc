// One particle against every sphere in file order, then every plane (docs/design.md §1.4), then
// every mesh collider (docs/model.md), as
// collide_objects in host/core/reference/reference.cpp. x is its position, d its displacement of this
// substep (x_prev = x - d); both change. Shared by collide_objects.comp and the passes it is
// fused into (advance, resolve_self_contacts).
#ifndef CLOTHSIM_COLLIDE_OBJECTS_GLSL
#define CLOTHSIM_COLLIDE_OBJECTS_GLSL

#include "particle_views.glsl"
#include "features.glsl"

// The friction blend x' = x_prev + keep (t - x_prev), as d' = keep ((t - x) + d),
// x' = x + (d' - d): only small differences are rounded.
void blend_to(vec3 t_minus_x, float keep, inout vec3 x, inout vec3 d) {
  precise vec3 next_d = (t_minus_x + d) * keep;
  precise vec3 next_x = x + (next_d - d);
  x = next_x;
  d = next_d;
}

// The blend relative to a collider that moved by m this substep (docs/model.md): in its frame
// x_prev is x_prev + m, so d' = keep ((t - x) + d - m) + m.
void blend_to_moving(vec3 t_minus_x, float keep, vec3 m, inout vec3 x, inout vec3 d) {
  precise vec3 next_d = ((t_minus_x + d) - m) * keep + m;
  precise vec3 next_x = x + (next_d - d);
  x = next_x;
  d = next_d;
}

// A moving sphere's push-out: along e = x - o, unless the motion relative to the sphere
// carried the mass past the centre this substep (e . e_prev < 0, e_prev = e - d + m): then back
// out on the side it came from, along e_prev, so that a fast sphere cannot pass through.
vec3 moving_sphere_push(vec3 e, float dist, float r, vec3 d, vec3 m) {
  precise vec3 e_prev = (e - d) + m;
  float prev_dist = length3(e_prev);
  if (dot3(e, e_prev) < 0.0 && prev_dist > 0.0) {
    precise float inv_prev = 1.0 / prev_dist;
    precise vec3 back = e_prev * (r * inv_prev) - e;
    return back;
  }
  if (!(dist > 0.0)) return vec3(0.0, r, 0.0);
  precise float scale = (r - dist) * (1.0 / dist);
  precise vec3 out_along_e = e * scale;
  return out_along_e;
}

// The first test of passed_through_sphere: a path of length |rel| that ends `dist - r` outside
// the sphere cannot have entered it. Also may_collide's, on the same values: the same decision.
bool path_stays_outside(float dist, float r, vec3 rel) {
  precise float gap = dist - r;
  float a = dot3(rel, rel);
  precise float gap2 = gap * gap;
  return !(a > gap2);
}

// A mass outside a sphere at the end of the substep (e = x - o, dist = |e| > r) that moved by
// rel = d - m relative to it: true if its path went into the sphere deeper than 0.1 mm, with
// t - x the push back to where the path entered the surface (passed_through_sphere in
// host/core/reference/reference_collisions.cpp).
bool passed_through_sphere(vec3 e, float dist, float r, vec3 rel, out vec3 t_minus_x) {
  t_minus_x = vec3(0.0);
  if (path_stays_outside(dist, r, rel)) return false;
  float a = dot3(rel, rel);
  precise vec3 e_prev = e - rel;
  float b = dot3(e_prev, rel);
  if (!(b < 0.0)) return false;
  precise float inv_a = 1.0 / a;
  precise float s_closest = min(1.0, -b * inv_a);
  precise vec3 closest = e_prev + rel * s_closest;
  precise float depth = r - length3(closest);
  if (!(depth > 1e-4)) return false;
  precise float c = dot3(e_prev, e_prev) - r * r;
  if (c > 0.0) {
    precise float disc = b * b - a * c;
    precise float s_in = (-b - sqrt(disc)) * inv_a;
    precise vec3 entry = (e_prev + rel * s_in) - e;
    t_minus_x = entry;
  } else {
    float prev_dist = length3(e_prev);
    precise float inv_prev = 1.0 / prev_dist;
    precise vec3 back = e_prev * (r * inv_prev) - e;
    precise vec3 up = vec3(0.0, r, 0.0) - e;
    t_minus_x = prev_dist > 0.0 ? back : up;
  }
  return true;
}

// After the friction blend (whose chord from x_prev can run inside the sphere), a mass deeper
// than 0.1 mm goes back to the surface along e, without friction (keep_out_of_sphere in
// host/core/reference/reference_collisions.cpp).
void keep_out_of_sphere(vec3 o, float r, inout vec3 x, inout vec3 d) {
  vec3 e = x - o;
  float dist = length3(e);
  precise float depth = r - dist;
  if (!(depth > 1e-4) || !(dist > 0.0)) return;
  precise float scale = depth * (1.0 / dist);
  precise vec3 out_along_e = e * scale;
  precise vec3 nx = x + out_along_e, nd = d + out_along_e;
  x = nx;
  d = nd;
}

// A mass deeper than 0.1 mm behind a plane's front goes to its surface offset on the front,
// along n, without friction (keep_in_front_of_plane in host/core/reference/reference_collisions.cpp).
void keep_in_front_of_plane(vec3 p, vec3 n, float front, inout vec3 x, inout vec3 d) {
  float dist = dot3(x - p, n);
  precise float behind = dist * front;
  if (!(behind < -1e-4)) return;
  precise float along = 1e-4 * front - dist;
  precise vec3 out_along_n = n * along;
  precise vec3 nx = x + out_along_n, nd = d + out_along_n;
  x = nx;
  d = nd;
}

// xpbd's contact response (coulomb_respond in host/core/reference/reference_collisions.cpp): the push
// along the outward contact normal n, then Coulomb friction on the substep's displacement
// relative to the collider: its tangential part cancelled up to mu times the push's depth along n.
void coulomb_respond(vec3 t_minus_x, vec3 n, float mu, vec3 m, inout vec3 x, inout vec3 d) {
  precise vec3 pushed = d + t_minus_x;
  float depth = dot3(t_minus_x, n);
  vec3 cancel = vec3(0.0);
  if (depth > 0.0 && mu > 0.0) {
    precise vec3 rel = pushed - m;
    precise vec3 tangential = rel - n * dot3(rel, n);
    float slide = length3(tangential);
    precise float limit = mu * depth;
    precise float inv_slide = 1.0 / slide;
    precise vec3 part = tangential * (limit * inv_slide);
    if (slide > 0.0) cancel = slide <= limit ? tangential : part;
  }
  precise vec3 next_x = x + (t_minus_x - cancel), next_d = pushed - cancel;
  x = next_x;
  d = next_d;
}

// The outward normal of a sphere at the point x + t_minus_x (up at the centre).
vec3 sphere_normal(vec3 o, vec3 x, vec3 t_minus_x) {
  precise vec3 e = (x + t_minus_x) - o;
  float len = length3(e);
  precise float inv = 1.0 / len;
  precise vec3 unit = e * inv;
  return len > 0.0 ? unit : vec3(0.0, 1.0, 0.0);
}

// A contact's response along the outward normal n (respond_to_contact in the reference):
// xpbd's Coulomb friction when `coulomb`, else the CS184 blend keeping `keep` (1: none), in the
// collider's frame when it moves by m.
void respond_to_contact(bool coulomb, vec3 t_minus_x, vec3 n, float keep, float mu, vec3 m, inout vec3 x,
                        inout vec3 d) {
  if (coulomb) coulomb_respond(t_minus_x, n, mu, m, x, d);
  else if (any(notEqual(m, vec3(0.0)))) blend_to_moving(t_minus_x, keep, m, x, d);
  else blend_to(t_minus_x, keep, x, d);
}

// One sphere contact's response (respond_to_sphere in the reference): xpbd's Coulomb friction
// (COULOMB_FRICTION, with friction on), else the CS184 blend, in the sphere's frame when
// it moves.
void respond_to_sphere(bool friction, vec3 o, float keep, float mu, vec3 m, vec3 t_minus_x, inout vec3 x,
                       inout vec3 d) {
  if (friction && COULOMB_FRICTION) coulomb_respond(t_minus_x, sphere_normal(o, x, t_minus_x), mu, m, x, d);
  else if (any(notEqual(m, vec3(0.0)))) blend_to_moving(t_minus_x, keep, m, x, d);
  else blend_to(t_minus_x, keep, x, d);
}

// The plane's crossing test in its frame (x_prev - p_prev = (x - p) - (d - m)): the signed
// distances of the substep's end and start, and whether they differ in sign (or one is 0).
bool plane_sides(vec3 x, vec3 d, vec4 point_front, vec3 n, vec3 m, out float dist, out float dist_prev) {
  dist = dot3(x - point_front.xyz, n);
  precise vec3 rel_d = d - m;
  precise float prev = dist - dot3(rel_d, n);
  dist_prev = prev;
  precise float crossing = dist * dist_prev;
  return !(crossing > 0.0);
}

// A mass that did not cross: untouched while it ends in front by more than the contact offset
// (1e-4 with Coulomb friction: resting contact) or, without, anywhere in front.
bool stays_in_front(float dist, float front, bool coulomb) {
  precise float ahead = dist * front;
  return !(ahead < (coulomb ? 1e-4 : 0.0));
}

#include "collide_meshes.glsl"

// With `friction` false every contact keeps all of its tangential motion (keep = 1): the pure
// push-out that xpbd's constraint pass applies after each correction (docs/model.md); applying
// it twice changes nothing.
void collide_with_objects_friction(inout vec3 x, inout vec3 d, bool friction) {
  for (int s = 0; s < sphere_count(); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    vec4 keep_mu = texelFetch(spheres_view, SPHERE_TEXELS * s + 1);
    float keep = friction ? keep_mu.x : 1.0;
    vec3 m = collider_motion(texelFetch(spheres_view, SPHERE_TEXELS * s + 2).xyz);
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
    } else if (any(notEqual(m, vec3(0.0)))) {
      t_minus_x = moving_sphere_push(e, dist, r, d, m);
    } else {
      // The push out along e, unless the mass passed the centre this substep: then back out on
      // its own side, along e_prev = e - d (a mass exactly at the centre goes up).
      frame_motion = vec3(0.0);
      precise vec3 e_prev = e - d;
      float prev_dist = length3(e_prev);
      if (dot3(e, e_prev) < 0.0 && prev_dist > 0.0) {
        precise float inv_prev = 1.0 / prev_dist;
        t_minus_x = e_prev * (r * inv_prev) - e;
      } else if (dist > 0.0) {
        precise float scale = (r - dist) * (1.0 / dist);
        t_minus_x = e * scale;
      } else {
        t_minus_x = vec3(0.0, r, 0.0);
      }
    }
    respond_to_sphere(friction, origin_radius.xyz, keep, keep_mu.y, frame_motion, t_minus_x, x, d);
    keep_out_of_sphere(origin_radius.xyz, r, x, d);
  }
  for (int k = 0; k < plane_count(); ++k) {
    vec4 point_front = texelFetch(planes_view, PLANE_TEXELS * k);
    vec4 normal_keep = texelFetch(planes_view, PLANE_TEXELS * k + 1);
    vec4 motion_mu = texelFetch(planes_view, PLANE_TEXELS * k + 2);
    vec3 m = collider_motion(motion_mu.xyz);
    vec3 n = normal_keep.xyz;
    float front = point_front.w;
    bool coulomb = friction && COULOMB_FRICTION;
    if (!friction) normal_keep.w = 1.0;
    // The classic crossing test (in the plane's frame, x_prev - p_prev = (x - p) - (d - m), so a
    // sweep is seen at any speed), and a mass found behind the front at both ends of the
    // substep is lifted to the front (docs/model.md); with Coulomb friction a mass within the
    // surface offset in front is in contact too (resting contact).
    float dist, dist_prev;
    bool crossed = plane_sides(x, d, point_front, n, m, dist, dist_prev);
    float side;
    if (!crossed) {
      if (stays_in_front(dist, front, coulomb)) continue;
      side = front;
    } else {
      side = dist_prev > 0.0 ? 1.0 : (dist_prev < 0.0 ? -1.0 : 0.0);
    }
    precise float along = 1e-4 * side - dist;
    precise vec3 t_minus_x = n * along;
    precise vec3 outward = n * (side != 0.0 ? side : front);
    respond_to_contact(coulomb, t_minus_x, outward, normal_keep.w, motion_mu.w, m, x, d);
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
  return plane_sides(x, d, point_front, n, m, dist, dist_prev) ||
         !stays_in_front(dist, point_front.w, friction && COULOMB_FRICTION);
}
bvec2 or_each(bvec2 may, bool i, bool j) { return bvec2(may.x || i, may.y || j); }

// Whether a sphere or a plane could change masses i and j (a spring's ends in a sweep): true
// where one may move it. Each collider's parameters are fetched once for both (on llvmpipe a
// fetch is a call, dearer than the tests).
bvec2 analytic_may_move_pair(vec3 xi, vec3 di, vec3 xj, vec3 dj, bool friction) {
  bvec2 may = bvec2(false);
  for (int s = 0; s < sphere_count(); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    vec3 m = collider_motion(texelFetch(spheres_view, SPHERE_TEXELS * s + 2).xyz);
    may = or_each(may, sphere_may_move(origin_radius, m, xi, di), sphere_may_move(origin_radius, m, xj, dj));
  }
  for (int k = 0; k < plane_count(); ++k) {
    vec4 point_front = texelFetch(planes_view, PLANE_TEXELS * k);
    vec3 n = texelFetch(planes_view, PLANE_TEXELS * k + 1).xyz;
    vec3 m = collider_motion(texelFetch(planes_view, PLANE_TEXELS * k + 2).xyz);
    may = or_each(may, plane_may_move(point_front, n, m, xi, di, friction),
                  plane_may_move(point_front, n, m, xj, dj, friction));
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
  return analytic_may_move_pair(x, d, x, d, friction).x || !meshes_alone;
}

// The same for masses i and j in the passes after predict (xpbd's and multigrid's sweeps), each
// with the clearance predict kept: the meshes decide without a field sample
// (mesh_leaves_alone_after), listing a mass near a mesh that the response may then leave
// alone. The passes list the masses it is true for, and collide_objects runs on those alone
// (compute/contact_list.glsl).
bvec2 may_collide_pair_after(vec3 xi, vec3 di, float ci, vec3 xj, vec3 dj, float cj, bool friction) {
  bvec2 may = analytic_may_move_pair(xi, di, xj, dj, friction);
  for (int k = 0; k < mesh_count(); ++k) {
    MeshField field = mesh_field(k);
    may = or_each(may, !mesh_leaves_alone_after(field, xi, di, ci), !mesh_leaves_alone_after(field, xj, dj, cj));
  }
  return may;
}

// A mass deeper than 0.1 mm inside a sphere, or behind a plane's front, goes back to the
// surface without friction (keep_out_of_colliders in host/core/reference/reference_collisions.cpp).
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
    keep_out_of_mesh(m, x, d);
  }
}

#endif

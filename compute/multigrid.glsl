// What the multigrid solver's passes share (docs/model.md, "One substep (fabric solver)"):
// the hierarchy's views and the coarse residual (a spring's Hessian terms and the 3x3 block's
// solve are compute/shared/springs.glsl's).
#ifndef CLOTHSIM_MULTIGRID_GLSL
#define CLOTHSIM_MULTIGRID_GLSL

#include "particle_views.glsl"
#include "shared/integration.glsl"
#include "shared/membrane.glsl"
#include "shared/springs.glsl"

layout(binding = TEXTURE_MG_VERTICES) uniform usamplerBuffer mg_vertices_view;
layout(binding = TEXTURE_MG_LISTS) uniform usamplerBuffer mg_lists_view;
layout(binding = TEXTURE_MG_FINE) uniform usamplerBuffer mg_fine_view;
layout(binding = TEXTURE_MG_ORDER) uniform usamplerBuffer mg_order_view;
layout(binding = TEXTURE_MG_CORR) uniform samplerBuffer mg_corr_view;
layout(binding = TEXTURE_MG_OFFSET) uniform samplerBuffer mg_offset_view;
layout(binding = TEXTURE_MG_RESIDUALS) uniform samplerBuffer mg_residuals_view;
layout(binding = TEXTURE_MG_RHS) uniform samplerBuffer mg_rhs_view;

// Particle i's offset x - y (predict wrote it, prolong_to_cloth and relax_vertices move it).
vec3 offset_of(int i) { return texelFetch(mg_offset_view, i).xyz; }

// Where the material's terms read particle j: now, or at the solve's start (plus its offset:
// compute_residuals).
vec3 material_position(int j, bool at_start) {
  precise vec3 p = position_of(j).xyz + offset_of(j);
  return at_start ? p : position_of(j).xyz;
}

// Particle i's bending block Q_ii plus the sum of k0^2 over its curved hinges (hinge_block in
// host/core/reference/reference_material.hpp, which says why).
float hinge_block(int i, Material mat) {
  precise float sum = 0.0;
  if (!(mat.moduli.x > 0.0)) return sum;
  uint first = bend_first(i);
  if (first < bend_first(i + 1)) sum = uintBitsToFloat(texelFetch(gather_view, int(first)).y);
  uint last = hinge_first(i + 1);
  for (uint e = hinge_first(i); e < last; e += 2u) {
    float k0 = uintBitsToFloat(texelFetch(gather_view, int(e) + 1).x);
    sum = sum + k0 * k0;
  }
  return sum;
}

// Particle i's membrane triangles, bending row and curved hinges at x (docs/materials.md):
// their forces added to f, their blocks to hess (the membrane's not at_start: the residual drops
// them), in that order. None without a material (moduli 0, and then no starts were uploaded to
// read). The CPU twin is add_material_terms in host/core/reference/reference_material.hpp.
vec3 add_material_terms(int i, Material mat, vec3 x, bool at_start, vec3 f, inout Sym3 hess) {
  if (!(mat.moduli.x > 0.0)) return f;
  uint last = membrane_first(i + 1);
  for (uint e = membrane_first(i); e < last; e += 2u) {
    uvec4 t = texelFetch(gather_view, int(e));
    vec4 dminv = uintBitsToFloat(texelFetch(gather_view, int(e) + 1));
    f = add_membrane_terms(f, hess, x, material_position(int(t.x), at_start), material_position(int(t.y), at_start),
                           dminv, uintBitsToFloat(t.z), mat.moduli, !at_start);
  }
  uint first = bend_first(i);
  last = bend_first(i + 1);
  if (first < last) add_spring_hessian(hess, vec3(0.0), 0.0, uintBitsToFloat(texelFetch(gather_view, int(first)).y));
  for (uint e = first; e < last; ++e) {
    uvec4 q = texelFetch(gather_view, int(e));
    f = add_bend_pull(f, x, material_position(int(q.x), at_start), uintBitsToFloat(q.y));
    f = add_bend_pull(f, x, material_position(int(q.z), at_start), uintBitsToFloat(q.w));
  }
  last = hinge_first(i + 1);
  for (uint e = hinge_first(i); e < last; e += 2u) {
    uvec4 o = texelFetch(gather_view, int(e));
    vec4 k = uintBitsToFloat(texelFetch(gather_view, int(e) + 1));
    f = add_hinge_terms(f, hess, x, material_position(int(o.x), at_start), material_position(int(o.y), at_start),
                        material_position(int(o.z), at_start), k, uintBitsToFloat(o.w));
  }
  return f;
}

// How a pass reads a residual, a right-hand side and a correction, each written by an earlier
// dispatch: through their views (a storage-buffer read in a loop is a bounds-checked loop over
// the lanes on llvmpipe), unless it defines these first. The one pass that reads what it wrote
// itself, cycle_small_levels, reads its coherent storage buffers.
#ifndef MG_RESIDUAL_OF
#define MG_RESIDUAL_OF(k) texelFetch(mg_residuals_view, int(k))
#endif
#ifndef MG_RHS_OF
#define MG_RHS_OF(g) texelFetch(mg_rhs_view, int(g))
#endif
#ifndef MG_CORR_OF
#define MG_CORR_OF(g) texelFetch(mg_corr_view, int(g))
#endif

// The range of this dispatch: vertices (or entries of the order) [u_first, u_first + u_count).
uniform uint u_first;
uniform uint u_count;

// A mass at x within CONTACT_REACH of a collider's surface, which holds it with a force the
// coarse problem does not know (touches_colliders in host/core/reference/reference_multigrid.cpp). The
// pass includes collide_objects.glsl first (spheres, planes, meshes).
#ifdef CLOTHSIM_COLLIDE_OBJECTS_GLSL
bool touches_colliders(vec3 x) {
  float reach = CONTACT_REACH;
  for (int s = 0; s < sphere_count(); ++s) {
    vec4 origin_radius = texelFetch(spheres_view, SPHERE_TEXELS * s);
    if (near_sphere(x, origin_radius.xyz, origin_radius.w, reach)) return true;
  }
  for (int k = 0; k < plane_count(); ++k) {
    vec4 point_front = texelFetch(planes_view, PLANE_TEXELS * k);
    vec3 n = texelFetch(planes_view, PLANE_TEXELS * k + 1).xyz;
    if (near_plane(x, point_front.xyz, n, point_front.w, reach)) return true;
  }
  for (int k = 0; k < mesh_count(); ++k) {
    MeshField m = mesh_field(k);
    float phi;
    vec3 grad;
    precise float within = m.thickness + reach;
    if (mesh_at(m, x, vec3(0.0)) && sample_mesh_field(m, mesh_local(m, x - m.origin), phi, grad) && phi < within) return true;
  }
  return false;
}
#endif

// Coarse vertex g: its particle, and its entries' ranges [first, last) in the lists.
uvec4 mg_vertex(uint g) { return texelFetch(mg_vertices_view, int(g)); }
uvec4 mg_entry(uint k) { return texelFetch(mg_lists_view, int(k)); }

// b - A e at coarse vertex g (its vertex row v, its restricted force and mass b), and A's
// diagonal block there: A = M / dt^2 + the coarse springs' Hessians at the current positions
// (coarse_residual).
vec3 coarse_residual(uint g, uvec4 v, vec4 b, out Sym3 diag) {
  precise float inertia = b.w * params.inv_dt2;
  vec3 e = MG_CORR_OF(g).xyz;
  vec3 p = position_of(int(v.x)).xyz;
  precise vec3 r = b.xyz - e * inertia;
  diag = sym3_diagonal(inertia);
  uint last = mg_vertex(g + 1u).w;
  for (uint k = v.w; k < last; ++k) {
    uvec4 s = mg_entry(k);  // x the other end, y rest bits, z stiffness bits, w its particle
    vec3 n;
    float len, sa, sd;
    if (!spring_terms(p, position_of(int(s.w)).xyz, uintBitsToFloat(s.y), uintBitsToFloat(s.z), n, len, sa,
                      sd))
      continue;
    precise vec3 dv = e - MG_CORR_OF(s.x).xyz;
    precise vec3 hv = spring_hessian_times(n, sa, sd, dv);
    r = r - hv;
    add_spring_hessian(diag, n, sa, sd);
  }
  return r;
}

#endif


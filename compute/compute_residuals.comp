// Reads positions and the offsets (through the views); writes the residuals of the particles. One invocation
// per particle, the multigrid solve's first pass (docs/model.md): the residual force of the
// implicit step at the start x = y + offset (predict's offset: minus the external forces'
// share), -m/dt^2 (x - y) + the springs' forces summed in the gather order (with a material,
// its triangles' and stencils': add_material_terms); w its mass, with its stencils' block as
// inertia (hinge_block), 0 for a pinned or held mass, which does not take part. The CPU twin is
// compute_residuals in host/core/reference/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"
#include "collide_objects.glsl"
#include "multigrid.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_MG_RESIDUALS) writeonly buffer Residuals { vec4 residual[]; };

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  if (p.w == 0.0) {
    residual[i] = vec4(0.0);
    return;
  }
  float mass;
  Material mat = material_and_mass_of(i, mass);
  // -m/dt^2 (x - y) + the springs' force (compute_residuals in host/core/reference/reference_multigrid.cpp).
  precise float inertia = mass * params.inv_dt2;
  vec3 off = offset_of(i);
  precise vec3 xi = p.xyz + off;
  // A mass a collider holds stays out of the coarse problem (touches_colliders).
  g_self = i;
  if (has_colliders() && touches_colliders(xi)) {
    residual[i] = vec4(0.0, 0.0, 0.0, mass);
    return;
  }
  precise vec3 f = off * -inertia;
  uint first = texelFetch(gather_start_view, i).x, last = texelFetch(gather_start_view, i + 1).x;
  for (uint g = first; g < last; ++g) {
    int j;
    uint type;
    float rest, k;
    if (!gathered_spring(g, mat, j, type, rest, k)) continue;
    precise vec3 e = (position_of(j).xyz + offset_of(j)) - xi;
    f = add_spring_force(f, e, rest, k);
  }
  Sym3 unused = sym3_diagonal(0.0);
  f = add_material_terms(i, mat, xi, true, f, unused);
  vec4 rel;
  vec3 origin;
  if (ATTACHMENTS && attachment_of(i, rel, origin)) f = add_anchor_pull(f, xi, rel.xyz, origin, rel.w);
  // The coarse problem weighs each mass with its hinges' block as inertia (hinge_block).
  precise float weight = mass + params.dt2 * hinge_block(i, mat);
  residual[i] = vec4(f, weight);
}

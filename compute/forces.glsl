// The force on one particle (docs/design.md §1.1): gravity plus its springs, summed in the model's
// gather order (ClothModel::gather: on a grid kGatherOrder, per direction the spring stored
// here, then the one stored at the neighbour behind); the spring's term is
// compute/shared/springs.glsl's.
#ifndef CLOTHSIM_FORCES_GLSL
#define CLOTHSIM_FORCES_GLSL

#include "particle_views.glsl"
#include "features.glsl"
#include "shared/springs.glsl"

vec3 add_spring(vec3 f, vec3 xi, int j, float rest, float k_spring) {
  return add_spring_force(f, position_of(j).xyz - xi, rest, k_spring);
}

// Only a seam joins two cloths (gathered_spring reads the other's ks for it): every other spring
// of particle i has i's material. (mass: particle i's, read with its material by the caller.)
vec3 spring_force(int i, vec3 xi, Material mat, float mass) {
  precise vec3 f = params.gravity * mass;
  uint first = texelFetch(gather_start_view, i).x, last = texelFetch(gather_start_view, i + 1).x;
  for (uint g = first; g < last; ++g) {
    int j;
    uint type;
    float rest, k;
    if (!gathered_spring(g, mat, j, type, rest, k)) continue;
    f = add_spring(f, xi, j, rest, k);
  }
  // An attachment's pull, after the springs (accumulate_forces in reference_forces.cpp).
  vec4 rel;
  vec3 origin;
  if (ATTACHMENTS && attachment_of(i, rel, origin)) f = add_anchor_pull(f, xi, rel.xyz, origin, rel.w);
  return f;
}

#endif

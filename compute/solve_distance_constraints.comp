// Reads (through the views) and writes positions, displacements and the springs' multipliers in place. The xpbd
// solver's constraint pass (docs/model.md): dispatched once per colour over that colour's
// springs (ClothModel::colour_start), one invocation per spring; no two springs of a
// colour share a particle, so the writes never race. Each spring's XPBD distance constraint is
// solved once (its multiplier starts at zero every substep), then max_stretch is enforced as a
// hard limit in the same visit. The CPU twin is solve_distance_constraint_colour.
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"
#include "collide_objects.glsl"
#include "contact_list.glsl"
#include "constraint_colour.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
layout(std430, binding = BINDING_MULTIPLIERS) writeonly buffer Multipliers { vec4 multiplier[]; };

void main() {
  int i, j, material_index;
  float rest;
  uint type;
  if (!colour_spring(gl_GlobalInvocationID.x, i, j, rest, type, material_index)) return;
  Material mat = material(material_index);
  if (!type_enabled(mat, type)) return;  // a cloth with this type off
  vec4 pi = position_of(i), pj = position_of(j);
  precise float wsum = pi.w + pj.w;
  if (wsum == 0.0) return;  // both ends pinned
  float alpha = compliance(mat, type);
  precise vec3 xi = pi.xyz, xj = pj.xyz;
  vec4 moved_i = displacement_of(i), moved_j = displacement_of(j);  // w: predict's clearance bounds (x - d stays)
  precise vec3 di = moved_i.xyz, dj = moved_j.xyz;
  precise vec3 e = xj - xi;
  float len = length3(e);
  if (len > 0.0) {
    // From the multiplier the spring ended the last substep with (predict applied it).
    uint k = u_first + gl_GlobalInvocationID.x;
    float lambda = texelFetch(multipliers_view, int(k)).w;
    vec3 n;
    float carried = xpbd_distance_step(e, len, rest, alpha, lambda, pi.w, pj.w, wsum, xi, xj, di, dj, n);
    multiplier[k] = vec4(n, carried);
  }
  // max_stretch stays a hard limit, in the same visit.
  limit_stretch(xi, xj, di, dj, pi.w, pj.w, wsum, params.stretch_limit * rest);
  // A correction must not push a mass into a collider or through a plane, where the collision
  // test of the next substep could no longer see it (docs/model.md).
  // Applied after this colour to the masses it lists (compute/contact_list.glsl).
  if (has_colliders())
    list_ends_if_collider_may_move(i, xi, di, moved_i.w, j, xj, dj, moved_j.w, bvec2(pi.w != 0.0, pj.w != 0.0));
  pos[i].xyz = xi;
  pos[j].xyz = xj;
  // Only xyz: w, predict's clearance bound, stays with x - d (llvmpipe stores a storage
  // buffer's vector component by component).
  disp[i].xyz = di;
  disp[j].xyz = dj;
}

// Reads (through the views) and writes positions and displacements in place. Dispatched once
// per colour over that colour's springs (ClothModel::colour_start): one invocation per spring
// of the colour, and no two springs of a colour share a particle, so the writes never
// race (Provot 1995). The CPU twin is solve_length_constraint_colour. Compiled with
// STRETCH_SETTLED (1 + 2^-16), a watched pass of enforce_stretch_limit: it also raises the
// settling flag where a spring is longer than that times its limit (limit_colour in
// host/core/reference/reference_constraints.cpp), for arm_stretch_pass to read.
#include "layout.glsl"
#include "common.glsl"
#include "particle_views.glsl"
#include "constraint_colour.glsl"
#include "collide_objects.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
#ifdef STRETCH_SETTLED
layout(std430, binding = BINDING_STRETCH_CONTROL) buffer Stretch { StretchControl stretch; };
#endif

void main() {
  int i, j, material_index;
  float rest;
  uint type;
  if (!colour_spring(gl_GlobalInvocationID.x, i, j, rest, type, material_index)) return;
  if (!type_enabled(material(material_index), type)) return;  // a cloth with this type off
  vec4 pi = position_of(i), pj = position_of(j);
  precise float wsum = pi.w + pj.w;
  if (wsum == 0.0) return;  // both ends pinned
  vec3 xi = pi.xyz, xj = pj.xyz;
  vec3 di = displacement_of(i).xyz, dj = displacement_of(j).xyz;
  precise float limit = params.stretch_limit * rest;
#ifdef STRETCH_SETTLED
  // Every invocation that raises the flag writes the same 1 (no atomic needed).
  precise float settled = limit * STRETCH_SETTLED;
  if (length3(xj - xi) > settled) stretch.state.x = 1u;
#endif
  if (!limit_stretch(xi, xj, di, dj, pi.w, pj.w, wsum, limit)) return;
  // Provot's pull may not leave a mass deeper than 0.1 mm inside a collider or behind a
  // plane (docs/model.md, "Colliders: contact that holds"); shallower, nothing changes.
  if (has_colliders()) {
    g_self = int(i);  // (a skinned collider's search starts from each end's last nearest triangle)
    if (pi.w != 0.0) keep_out_of_colliders(xi, di);
    g_self = int(j);
    if (pj.w != 0.0) keep_out_of_colliders(xj, dj);
  }
  pos[i].xyz = xi;
  pos[j].xyz = xj;
  // Only xyz: w, a clearance bound where predict left one, stays valid with x - d.
  disp[i].xyz = di;
  disp[j].xyz = dj;
}

// Reads positions and displacements (through the views) and the offsets; writes positions,
// displacements and offsets of one colour of particles. One invocation per particle of the
// colour (entries [u_first, u_first + u_count) of the order): a Newton step of the implicit
// step's energy on the mass's 3x3 block, f = -m/dt^2 (x - y) + its springs' forces (with a
// material, its triangles' and bending stencils' instead: add_material_terms; with
// self-collision, its contacts'), H = m/dt^2 I + their Hessians; then max_stretch as a hard limit
// and the colliders' push-out. No spring
// joins two particles of a colour, so the writes never race with a read. The CPU twin is
// relax_vertices in host/core/reference/reference_multigrid.cpp.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"
#include "multigrid.glsl"
#include "spatial_hash.glsl"
#include "shared/self_contact.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
layout(std430, binding = BINDING_MG_OFFSET) writeonly buffer Offsets { vec4 offset[]; };
// The hash collide_self built this substep (its ids; the positions are read as they are now).
layout(std430, binding = BINDING_CELL_ENTRIES) readonly buffer Entries { uint entries[]; };

// A correction must not push a mass into a collider or through a plane;
// with Coulomb friction under fabric (params.sweep_friction), as the prediction's contacts are.
// Inline, in this dispatch (the mass's own state only, and no mass of the colour reads
// another's), as a loop of one trip or none rather than an if: llvmpipe runs an if's body for
// every lane, taken or not, but skips a loop that no lane of the batch enters, so a batch with
// no mass near a collider pays only may_collide_after's test (the contact list's reason,
// compute/contact_list.glsl, without its dispatch after each colour). u_count (at least 1) is
// the bound, not 1, so that the compiler cannot see the loop has one trip and make it an if.
void push_out(int i, inout vec3 x, inout vec3 d, float clearance) {
  bool push = may_collide_after(i, x, d, clearance, params.sweep_friction != 0u);
  for (uint trip = 0u; trip < (push ? u_count : 0u); trip = u_count) {
    g_self = i;
    g_friction_still_only = true;
    collide_with_objects_friction(x, d, params.sweep_friction != 0u);
  }
}

// Particle i's colour in this sweep (after the per-particle starts of TEXTURE_MG_FINE).
uint fine_colour_of(int i) { return texelFetch(mg_fine_view, int(particle_count()) + 1 + i).x; }

// The self-contacts of mass i (of `colour`) at x, which began the substep at start_i, with the
// masses of entries [first, last) (sweep_contact_keep, add_self_contact_pull). A mass of i's own colour is being moved by this dispatch: left to
// resolve_self_contacts.
void add_contacts(vec3 x, vec3 start_i, vec4 rest_i, uint colour, float k, uint first, uint last, inout vec3 f,
                  inout Sym3 hess) {
  for (uint e = first; e < last; ++e) {
    int j = int(entries[e]);
    vec3 xj = position_of(j).xyz;
    precise vec3 e3 = x - xj;
    float d = length3(e3);
    if (d >= params.contact_distance || d == 0.0 || fine_colour_of(j) == colour) continue;
    precise vec3 start_j = xj - displacement_of(j).xyz;
    float keep = sweep_contact_keep(start_i - start_j, params.contact_distance);
    if (d >= keep) continue;
    vec4 rest_j = texelFetch(rest_positions_view, j);
    if (params.welds != 0u && rest_j.w == rest_i.w) continue;  // a sewn pair
    if (!apart_at_rest(rest_i.xyz, rest_j.xyz, params.contact_distance)) continue;  // neighbours
    vec3 n;
    f = add_self_contact_pull(f, e3, d, keep, k, n);
    add_spring_hessian(hess, n, k, 0.0);
  }
}

// Every mass in the buckets of the 27 cells around x, in resolve_self_contacts' order (dz, dy,
// then the row's three buckets), each bucket once: where two rows' runs of buckets overlap (rows
// hashed onto each other; in a small table, always) the later skips what an earlier one took.
// Unlike the push-out, a bucket's masses of other cells are not filtered out by cell: they are
// far, and the distance test drops them.
void add_self_contacts(int i, vec3 x, vec3 start_i, float k, inout vec3 f, inout Sym3 hess) {
  ivec3 c = cell_of(x);
  vec4 rest_i = texelFetch(rest_positions_view, i);
  uint colour = fine_colour_of(i), mask = params.table_size - 1u;
  uint runs[9];
  for (int r = 0; r < 9; ++r) {
    runs[r] = (hash_row(c.y + r % 3 - 1, c.z + r / 3 - 1) + uint(c.x - 1)) & mask;
    for (uint dx = 0u; dx < 3u; ++dx) {
      uint b = (runs[r] + dx) & mask;
      bool taken = false;
      for (int q = 0; q < r; ++q) taken = taken || ((b - runs[q]) & mask) < 3u;
      if (!taken) add_contacts(x, start_i, rest_i, colour, k, texelFetch(cell_start_view, int(b)).x, texelFetch(cell_start_view, int(b) + 1).x, f, hess);
    }
  }
}

void main() {
  if (gl_GlobalInvocationID.x >= u_count) return;
  int i = int(texelFetch(mg_order_view, int(u_first + gl_GlobalInvocationID.x)).x);
  vec4 p = position_of(i);
  float wi = p.w;
  if (wi == 0.0) return;
  vec4 moved = displacement_of(i);  // w: predict's clearance bound (x - d stays)
  precise vec3 x = p.xyz, d = moved.xyz, off = offset_of(i);
  float mass;
  Material mat = material_and_mass_of(i, mass);
  precise float inertia = mass * params.inv_dt2;
  precise vec3 f = off * -inertia;
  Sym3 hess = sym3_diagonal(inertia);
  uint first = texelFetch(gather_start_view, i).x, last = texelFetch(gather_start_view, i + 1).x;
  // The least room any spring has left below 99 % of its limit, for skipping the limit's loop.
  float headroom = 3.0e38;
  for (uint g = first; g < last; ++g) {
    int j;
    uint type;
    float rest, k;
    if (!gathered_spring(g, mat, j, type, rest, k)) continue;
    vec3 n;
    float len, sa, sd;
    bool taut = spring_terms(x, position_of(j).xyz, rest, k, n, len, sa, sd);
    // A seam's limit is enforce_stretch_limit's (its weld): this loop moves one end at a time.
    if (type != SEAM_SPRING) headroom = min(headroom, 0.99 * params.stretch_limit * rest - len);
    if (!taut) continue;
    f = add_spring_pull(f, n, len, rest, k);
    add_spring_hessian(hess, n, sa, sd);
  }
  f = add_material_terms(i, mat, x, false, f, hess);
  // An attachment: its pull and its block k I (docs/model.md, "Attachments").
  vec4 rel;
  vec3 origin;
  if (ATTACHMENTS && attachment_of(i, rel, origin)) {
    f = add_anchor_pull(f, x, rel.xyz, origin, rel.w);
    add_spring_hessian(hess, vec3(0.0), 0.0, rel.w);
  }
  // fabric's sweep only (sweep_friction marks it): multigrid keeps the behaviour measured for it.
  if (params.bounded_contact != 0u && params.sweep_friction != 0u) add_self_contacts(i, x, x - d, float(SELF_CONTACT_STIFFNESS) * mat.stiffness.x, f, hess);
  vec3 step;
  uint limit_last = first;
  if (solve3(hess, f, step)) {
    x = x + step;
    d = d + step;
    off = off + step;
  }
  // max_stretch as a hard limit: each spring still longer than (1 + max_stretch) rest pulls
  // this mass its share of the way back (Provot's projection, one end at a time). A spring
  // grows by at most |step| (its other end stays: no spring joins two masses of a colour), so
  // where every spring had more room than that, with a margin far above the rounding, none
  // can be over its limit and the loop is cut to no trips. On llvmpipe a loop runs as often as
  // its longest lane (an if runs whether taken or not), so this saves most of the loop's cost
  // where the cloth is within its limit; the CPU twin runs the loop and finds nothing to do:
  // the same bits.
  if (!(length3(step) + 1.0e-6 * (length3(x) + 1.0) < headroom)) limit_last = last;
  for (uint g = first; g < limit_last; ++g) {
    int j;
    uint type;
    float rest, k;
    if (!gathered_spring(g, mat, j, type, rest, k) || type == SEAM_SPRING) continue;
    vec4 q = position_of(j);
    precise vec3 e = q.xyz - x;
    float len = length3(e);
    precise float limit = params.stretch_limit * rest;
    if (!(len > limit)) continue;
    vec3 corr = one_end_stretch_pull(e, len, limit, wi, q.w);
    x = x + corr;
    d = d + corr;
  }
  if (has_colliders()) push_out(i, x, d, moved.w);
  // Only xyz, every w unchanged (as in prolong_to_cloth).
  pos[i].xyz = x;
  disp[i].xyz = d;
  offset[i].xyz = off;
}

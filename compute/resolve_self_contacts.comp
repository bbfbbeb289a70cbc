// Reads positions, the bucket starts and the positions in cell order (sort_cells wrote them,
// so a candidate costs one read, not an id and then a position); writes the Jacobi output
// positions and, in place, the displacements. One invocation per particle: it visits the 27 cells around it and averages the
// push-out from every particle closer than 2 * thickness (docs/design.md §1.3), in the order of
// resolve_self_contacts in host/core/reference/reference.cpp. The last stage of collide_self, after
// count_cells, scan_cells, fill_cells and sort_cells built the hash. With u_collide_objects the collision objects follow in the same
// invocation (step 4 reads only the particle's own position and displacement).
#include "layout.glsl"
#include "common.glsl"
#include "spatial_hash.glsl"
#include "shared/self_contact.glsl"
#include "collide_objects.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS_OUT) writeonly buffer Output { vec4 pos_out[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };
// Particle ids in cell order: the bounded contact looks up a touching mass's rest position.
layout(std430, binding = BINDING_CELL_ENTRIES) readonly buffer Entries { uint entries[]; };

uniform bool u_collide_objects;

struct Contacts {
  vec3 sum;   // of the push-outs so far
  uint hits;  // particles within the contact distance so far
};

// Adds the push-out from every particle among entries [first, last) that lies in one of the
// three cells (x - 1 .. x + 1, row.y, row.z) and closer than the contact distance.
Contacts visit_entries(Contacts acc, vec3 xi, vec4 rest_i, ivec3 row, uint first, uint last) {
  float contact = params.contact_distance;
  for (uint e = first; e < last; ++e) {
    vec3 xj = texelFetch(sorted_positions_view, int(e)).xyz;
    // Buckets also hold cells of other rows that hash to them: count j only if it is in one
    // of this row's three cells, so nobody is counted twice however rows collide in the
    // table. i itself (and any particle exactly on it) has d == 0 and is skipped like the
    // reference's j == i.
    ivec3 cj = cell_of(xj);
    if (cj.yz != row.yz || abs(cj.x - row.x) > 1) continue;
    vec3 e3 = xi - xj;
    float d = length3(e3);
    if (d >= contact || d == 0.0) continue;
    // A touching pair only: its rest texel (xyz the rest position, w the weld). A sewn pair, one
    // weld, is held together by its seam, never pushed apart.
    vec4 rest_j = params.bounded_contact != 0u || params.welds != 0u ? texelFetch(rest_positions_view, int(entries[e]))
                                                                    : vec4(0.0);
    if (params.welds != 0u && rest_j.w == rest_i.w) continue;
    if (params.bounded_contact == 0u) {
      acc.sum = add_self_contact(acc.sum, e3, d, contact, 1.0);
      ++acc.hits;
      continue;
    }
    // Bounded contact: masses closer at rest than the contact distance (the cloth's own
    // neighbours) are kept only at their rest distance; each of the pair moves half the gap.
    // Read only for a touching pair, so the rest positions cost nothing in the common case.
    float keep = bounded_keep(rest_i.xyz, rest_j.xyz, contact);
    if (!(d < keep)) continue;
    acc.sum = add_self_contact(acc.sum, e3, d, keep, 0.5);
    ++acc.hits;
  }
  return acc;
}

uint bucket_start(uint b) { return texelFetch(cell_start_view, int(b)).x; }

// The three cells (x - 1 .. x + 1) of row (y, z) around cell c: three consecutive buckets,
// so one run of entries, in the reference's order (dx = -1, 0, 1; ascending ids within a
// cell) -- or two runs when the three buckets wrap around the end of the table.
Contacts visit_row(Contacts acc, vec3 xi, vec4 rest_i, ivec3 c, int dy, int dz) {
  ivec3 row = ivec3(c.x, c.y + dy, c.z + dz);
  uint size = params.table_size;
  uint b0 = (hash_row(row.y, row.z) + uint(c.x - 1)) & (size - 1u);
  uint end = b0 + 3u;
  acc = visit_entries(acc, xi, rest_i, row, bucket_start(b0), bucket_start(min(end, size)));
  if (end > size) acc = visit_entries(acc, xi, rest_i, row, bucket_start(0u), bucket_start(end - size));
  return acc;
}


void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  if (p.w == 0.0) {
    pos_out[i] = p;
    return;
  }
  precise vec3 xi = p.xyz;
  ivec3 c = cell_of(xi);
  Contacts acc = Contacts(vec3(0.0), 0u);
  // (Without the bounded contact or seams the view holds one dummy texel: not read.)
  vec4 rest_i = params.bounded_contact != 0u || params.welds != 0u ? texelFetch(rest_positions_view, i) : vec4(0.0);
  // The nine rows of three cells, in the reference's order (dz, then dy), written out so
  // every offset is a constant.
  acc = visit_row(acc, xi, rest_i, c, -1, -1);
  acc = visit_row(acc, xi, rest_i, c, 0, -1);
  acc = visit_row(acc, xi, rest_i, c, 1, -1);
  acc = visit_row(acc, xi, rest_i, c, -1, 0);
  acc = visit_row(acc, xi, rest_i, c, 0, 0);
  acc = visit_row(acc, xi, rest_i, c, 1, 0);
  acc = visit_row(acc, xi, rest_i, c, -1, 1);
  acc = visit_row(acc, xi, rest_i, c, 0, 1);
  acc = visit_row(acc, xi, rest_i, c, 1, 1);
  precise vec3 sum = acc.sum;
  uint hits = acc.hits;
  vec4 moved = displacement_of(i);  // w: predict's clearance bound (x - d stays)
  precise vec3 d = moved.xyz;
  if (hits > 0u) {
    // Classic: the average over the contacts, spread over the substeps (docs/design.md §1.3).
    // Bounded: the average, whole, every substep.
    float scale = self_contact_scale(hits, params.bounded_contact != 0u, params.steps);
    precise vec3 corr = sum * scale;
    xi = xi + corr;
    d = d + corr;  // x_prev stays where it was
  }
  g_self = i;  // the substep's first collision: a skinned collider's nearest triangle searched for
  g_search = true;
  if (u_collide_objects) collide_with_objects(xi, d);
  disp[i].xyz = d;  // w, predict's clearance bound, stays with x - d
  pos_out[i] = vec4(xi, p.w);
}

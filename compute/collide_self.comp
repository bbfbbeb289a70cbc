// Reads positions and the sorted hashed grid; writes the Jacobi output positions. One
// invocation per particle: it visits the 27 cells around it and averages the push-out from
// every particle closer than 2 * thickness (DESIGN.md §1.3), in the reference's order.
#include "layout.glsl"
#include "common.glsl"
#include "spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) readonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_CELL_START) readonly buffer Starts { uint cell_start[]; };
layout(std430, binding = BINDING_CELL_ENTRIES) readonly buffer Entries { uint entries[]; };
layout(std430, binding = BINDING_POSITIONS_OUT) writeonly buffer Output { vec4 pos_out[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= particle_count()) return;
  vec4 p = pos[i];
  pos_out[i] = p;
  if (p.w == 0.0) return;
  vec3 xi = p.xyz;
  ivec3 c = cell_of(xi);
  float contact = params.constraint.y;
  precise vec3 sum = vec3(0.0);
  uint hits = 0u;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 cell = c + ivec3(dx, dy, dz);
        uint b = hash_cell(cell);
        for (uint e = cell_start[b]; e < cell_start[b + 1u]; ++e) {
          uint j = entries[e];
          vec3 xj = pos[j].xyz;
          // A bucket holds every cell that hashes to it: count j only in its own cell, so a
          // neighbour is never counted twice however the 27 cells collide in the table.
          if (j == i || cell_of(xj) != cell) continue;
          vec3 e3 = xi - xj;
          float d = length3(e3);
          if (d >= contact || d == 0.0) continue;
          precise float push = (contact - d) * (1.0 / d);
          sum = sum + e3 * push;
          ++hits;
        }
      }
  if (hits > 0u) {
    precise float scale = 1.0 / (float(hits) * params.constraint.w);
    precise vec3 moved = xi + sum * scale;
    pos_out[i] = vec4(moved, p.w);
  }
}

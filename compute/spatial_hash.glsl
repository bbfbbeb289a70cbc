// The hashed uniform grid, GLSL twin of host/core/spatial_hash.hpp: same cell coordinates
// (floor of a multiplication) and the same 32-bit hash, so both sides bucket alike.
#ifndef CLOTHSIM_SPATIAL_HASH_GLSL
#define CLOTHSIM_SPATIAL_HASH_GLSL

ivec3 cell_of(vec3 p) {
  precise vec3 scaled = p * params.constraint.z;
  return ivec3(floor(scaled));
}

// Rows (y, z) scattered, consecutive buckets along x (see hash_cell in spatial_hash.hpp).
uint hash_row(int y, int z) { return (uint(y) * 19349663u) ^ (uint(z) * 83492791u); }
uint hash_cell(ivec3 c) { return (hash_row(c.y, c.z) + uint(c.x)) & (params.grid.w - 1u); }

#endif

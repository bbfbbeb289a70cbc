// The hashed uniform grid, GLSL twin of host/core/spatial_hash.hpp: same cell coordinates
// (floor of a multiplication) and the same 32-bit hash, so both sides bucket alike.
#ifndef CLOTHSIM_SPATIAL_HASH_GLSL
#define CLOTHSIM_SPATIAL_HASH_GLSL

ivec3 cell_of(vec3 p) {
  precise vec3 scaled = p * params.constraint.z;
  return ivec3(floor(scaled));
}

uint hash_cell(ivec3 c) {
  uint h = (uint(c.x) * 73856093u) ^ (uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u);
  return h & (params.grid.w - 1u);
}

#endif

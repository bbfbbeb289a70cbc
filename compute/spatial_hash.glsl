// The hashed uniform grid of self-collision. The hash is written once for both languages
// (compute/shared/dialect.glsl); host/core/reference/spatial_hash.hpp includes this file. Rows (y, z) are
// scattered by the products; along x consecutive cells get consecutive buckets, so the three
// cells of a row that a particle visits are three adjacent buckets: one contiguous run of
// entries (resolve_self_contacts.comp reads them as one range; the table has at least 4
// buckets, so the three are distinct). 32-bit wrap-around products, xor, add, mask.
#ifndef CLOTHSIM_SPATIAL_HASH_GLSL
#define CLOTHSIM_SPATIAL_HASH_GLSL

#include "shared/dialect.glsl"

// Cell coordinates are clamped to +-CELL_LIMIT before they become integers: a float-to-int
// conversion of NaN or of anything past 2^31 is undefined in C++ and GLSL alike. A NaN goes
// to -CELL_LIMIT. Far inside the limit no cloth notices (a cell is millimetres).
#define CELL_LIMIT 1073741824.0  // 2^30

SHARED_BEGIN

SHARED uint hash_row(int y, int z) { return (uint(y) * 19349663u) ^ (uint(z) * 83492791u); }
SHARED uint hash_cell(int x, int y, int z, uint table_size) { return (hash_row(y, z) + uint(x)) & (table_size - 1u); }

// The integer cell of a coordinate scaled by 1 / cell (a multiplication, so both sides round
// alike): its floor, clamped as above.
SHARED_FN int cell_axis(REAL scaled) {
  REAL f = floor(scaled);
  if (!(f >= REAL(-CELL_LIMIT))) f = REAL(-CELL_LIMIT);  // also NaN
  if (f > REAL(CELL_LIMIT)) f = REAL(CELL_LIMIT);
  return int(f);
}

SHARED_END

#ifndef __cplusplus

ivec3 cell_of(vec3 p) {
  precise vec3 scaled = p * params.inv_cell;
  return ivec3(cell_axis(scaled.x), cell_axis(scaled.y), cell_axis(scaled.z));
}

uint hash_cell(ivec3 c) { return hash_cell(c.x, c.y, c.z, params.table_size); }
#endif

#endif

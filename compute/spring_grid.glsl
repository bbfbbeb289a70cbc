// Springs implicit in the grid, written once for both languages (compute/shared.glsl): the
// offset and type of each spring direction (DIR_* in layout.glsl) and the colour of each
// spring. host/core/spring_grid.hpp builds its tables from these; the passes call them with
// constant directions, so they fold away.
#ifndef CLOTHSIM_SPRING_GRID_GLSL
#define CLOTHSIM_SPRING_GRID_GLSL

#include "layout.glsl"
#include "shared.glsl"

SHARED_BEGIN

// Spring types as the SpringType enum: 0 structural, 1 shearing, 2 bending. Directions come
// in pairs of one type (DIR_RIGHT, DIR_DOWN structural; the diagonals shearing; the two-steps
// bending).
SHARED int direction_type(int direction) { return direction >> 1; }

// The spring of `direction` stored at (x, y) runs to (x + dx, y + dy).
SHARED int direction_dx(int direction) {
  return direction == DIR_RIGHT || direction == DIR_DIAG_DOWN_RIGHT ? 1
       : direction == DIR_DIAG_DOWN_LEFT                            ? -1
       : direction == DIR_RIGHT2                                    ? 2
                                                                    : 0;
}
SHARED int direction_dy(int direction) {
  return direction == DIR_DOWN || direction == DIR_DIAG_DOWN_RIGHT || direction == DIR_DIAG_DOWN_LEFT ? 1
       : direction == DIR_DOWN2                                                                      ? 2
                                                                                                     : 0;
}

// Colour of the spring of `direction` stored at (x, y): 2 * direction + parity, and no two
// springs of one colour share a particle. For unit steps the parity of the coordinate the
// spring advances along separates springs that share an end; two-steps need (coord / 2) % 2.
// Diagonals advance in y.
SHARED int spring_colour(int direction, int x, int y) {
  return 2 * direction + (direction == DIR_RIGHT    ? (x & 1)
                          : direction == DIR_RIGHT2 ? ((x >> 1) & 1)
                          : direction == DIR_DOWN2  ? ((y >> 1) & 1)
                                                    : (y & 1));
}

SHARED_END

#ifndef __cplusplus
ivec2 direction_offset(int direction) { return ivec2(direction_dx(direction), direction_dy(direction)); }

bool spring_type_enabled(int type) {
  return (type == 0 ? params.structural_enabled : type == 1 ? params.shearing_enabled : params.bending_enabled) != 0u;
}
bool spring_enabled(int direction) { return spring_type_enabled(direction_type(direction)); }
#endif

#endif

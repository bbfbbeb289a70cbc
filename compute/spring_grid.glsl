// Springs implicit in the grid; the GLSL twin of host/core/spring_grid.hpp.
#ifndef CLOTHSIM_SPRING_GRID_GLSL
#define CLOTHSIM_SPRING_GRID_GLSL

// Offset and type (0 structural, 1 shearing, 2 bending) of each DIR_*.
const ivec2 DIRECTION_OFFSET[NUM_DIRECTIONS] =
    ivec2[](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(-1, 1), ivec2(2, 0), ivec2(0, 2));
const uint DIRECTION_TYPE[NUM_DIRECTIONS] = uint[](0u, 0u, 1u, 1u, 2u, 2u);

bool spring_enabled(int direction) { return params.enabled[DIRECTION_TYPE[direction]] != 0u; }

#endif

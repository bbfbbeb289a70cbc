// The one source of truth for the GPU data layout, compiled by both C++ and GLSL.
// std430 for storage buffers, std140 for the parameter block; every struct member is a
// vec4/uvec4 so the two rules and the C++ compiler all agree (a vec3[] would have a
// 16-byte stride in GLSL and 12 in C++). tests/test_gpu_layout.cpp asks GL for the real
// offsets and strides and compares them with sizeof/offsetof here.
#ifndef CLOTHSIM_LAYOUT_GLSL
#define CLOTHSIM_LAYOUT_GLSL

#ifdef __cplusplus
#include <cstdint>
#include <glm/vec4.hpp>
namespace layout {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#endif

// Shader-storage buffer bindings (one per per-particle stream).
#define BINDING_POSITIONS 0   // vec4: xyz position, w inverse mass (0 = pinned)
#define BINDING_PREVIOUS 1    // vec4: xyz position one substep ago
#define BINDING_FORCES 2      // vec4: xyz force of this substep
#define BINDING_NORMALS 3     // vec4: xyz unit vertex normal
#define BINDING_REST 4        // RestLengths per particle
#define BINDING_SPHERES 5     // SphereCollider[]
#define BINDING_PLANES 6      // PlaneCollider[]
#define BINDING_POSITIONS_OUT 7  // vec4: Jacobi output of self-collision
#define BINDING_CELL_COUNT 8     // uint per hash bucket
#define BINDING_CELL_START 9     // uint per hash bucket (+1 sentinel)
#define BINDING_CELL_ENTRIES 10  // uint particle id, in cell order
#define BINDING_SCAN_SUMS 11     // uint per scan block (multi-level prefix sum)
#define BINDING_SCAN_DATA 12     // uint array being scanned in place
#define BINDING_MESH_EXTRA 13    // MeshVertex extras (uv, tangent) of collider meshes, for the render shaders
#define BINDING_SORTED_POSITIONS 14  // vec4: positions in cell order (entries order), for collide_self
#define BINDING_FRAME_BOUNDS 15  // FrameBounds of one frame (check_divergence)
#define BINDING_LAST_GOOD 16     // LastGoodHeader, then vec4 per particle: newest frame that passed (keep_last_good)
// Texture units of the read-only texel views (GL_TEXTURE_BUFFER) of the same buffers, through
// which the hot passes read (compute/particle_views.glsl says why).
#define TEXTURE_POSITIONS 0         // RGBA32F, one texel per particle
#define TEXTURE_PREVIOUS 1          // RGBA32F, one texel per particle
#define TEXTURE_REST 2              // RGBA32F, two texels per particle (RestLengths)
#define TEXTURE_SPHERES 3           // RGBA32F, two texels per SphereCollider
#define TEXTURE_PLANES 4            // RGBA32F, two texels per PlaneCollider
#define TEXTURE_CELL_START 5        // R32UI, one texel per hash bucket (+1 sentinel)
#define TEXTURE_SORTED_POSITIONS 6  // RGBA32F, one texel per hash entry
// Uniform block binding.
#define BINDING_STEP_PARAMS 0

// Threads per workgroup for every per-particle pass (a 1-D dispatch over the particle index).
#ifndef WORKGROUP_SIZE
#define WORKGROUP_SIZE 128
#endif
// Elements one invocation of scan_cells sums serially (the block of the multi-level scan).
#define SCAN_CHUNK 32
// Workgroup shape of the passes dispatched over the grid (x along a row): 2-D, so no
// invocation divides its index by the width, and neighbours share a workgroup.
#ifndef GRID_WORKGROUP_X
#define GRID_WORKGROUP_X 32
#endif
#ifndef GRID_WORKGROUP_Y
#define GRID_WORKGROUP_Y 4
#endif

// Spring directions stored at their "first" particle: the rest length of the spring from
// (x, y) to (x + dx, y + dy) lives at particle (x, y). The other six directions of a
// particle's twelve springs are these seen from the far end.
#define DIR_RIGHT 0       // structural (+1, 0)
#define DIR_DOWN 1        // structural (0, +1)
#define DIR_DIAG_DOWN_RIGHT 2  // shearing (+1, +1)
#define DIR_DIAG_DOWN_LEFT 3   // shearing (-1, +1)
#define DIR_RIGHT2 4      // bending (+2, 0)
#define DIR_DOWN2 5       // bending (0, +2)
#define NUM_DIRECTIONS 6
// Two colours per direction: no two springs of one colour share a particle.
#define NUM_COLOURS 12

struct RestLengths {
  vec4 near;  // rest length of DIR_RIGHT, DIR_DOWN, DIR_DIAG_DOWN_RIGHT, DIR_DIAG_DOWN_LEFT (0 if absent)
  vec4 far;   // rest length of DIR_RIGHT2, DIR_DOWN2, unused, unused
};

struct SphereCollider {
  vec4 origin_radius;  // xyz origin, w radius
  vec4 keep;           // x = 1 - friction
};

struct PlaneCollider {
  vec4 point;   // xyz a point on the plane
  vec4 normal;  // xyz unit normal, w = 1 - friction
};

// Per-vertex extras of a collider mesh (the cloth derives them from its grid instead).
struct MeshVertex {
  vec4 uv;       // xy texture coordinates
  vec4 tangent;  // xyz unit tangent along +u
};

// Everything a pass needs that is constant over a substep. Built on the host from the
// same Constants<float> the CPU reference uses, so both sides see identical floats.
struct StepParams {
  vec4 gravity_mass;   // xyz gravity (m/s^2), w particle mass (kg)
  vec4 springs;        // x ks, y bending ks (0.2 ks), z velocity keep (1 - damping/100), w dt^2
  vec4 constraint;     // x 1 + max_stretch, y self-collision distance (2 thickness), z cell size, w simulation_steps (as float)
  uvec4 grid;          // x width points, y height points, z particle count, w hash table size
  uvec4 enabled;       // x structural, y shearing, z bending (1 = exerts force / is constrained), w unused
  uvec4 colliders;     // x sphere count, y plane count
};

// The divergence guard's reduction of one frame. Coordinates are stored as ordered bits
// (compute/divergence.glsl): uints whose unsigned order is the float order, so that
// atomicMin/atomicMax reduce them.
struct FrameBounds {
  uvec4 lo;  // xyz smallest finite coordinate (ordered bits), w 1 if any coordinate is NaN/Inf
  uvec4 hi;  // xyz largest finite coordinate (ordered bits), w unused
};

// In front of the kept positions of keep_last_good.
struct LastGoodHeader {
  uvec4 state;  // x 1 once a frame has failed (no later frame is kept), y the frame kept, zw unused
};

#ifdef __cplusplus
}  // namespace layout
#endif
#endif

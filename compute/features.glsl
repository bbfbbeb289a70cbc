// What a pass is compiled with (host/gpu/shader_features.hpp; the host compiles the passes
// again when a live edit changes any of it): the collider kinds the scene has, whether a
// collider or a pin moves, the contact response, the wind, attachments and skinned colliders.
// Each is a compile-time constant there, so the code of what the scene cannot reach is
// not in the program at all: llvmpipe runs every branch of a shader whatever the data, so code that no
// mass takes still costs its full time there (docs/performance.md, "Passes compiled for the
// scene"), and a GPU saves the registers. Without the defines (a pass compiled on its own)
// everything is in, chosen at run time from the step parameters.
#ifndef CLOTHSIM_FEATURES_GLSL
#define CLOTHSIM_FEATURES_GLSL

#ifndef COLLIDE_SPHERES
#define COLLIDE_SPHERES true
#endif
#ifndef COLLIDE_PLANES
#define COLLIDE_PLANES true
#endif
#ifndef COLLIDE_MESHES
#define COLLIDE_MESHES true
#endif
#ifndef COLLIDERS_MOVE
#define COLLIDERS_MOVE true
#endif
#ifndef COULOMB_FRICTION
#define COULOMB_FRICTION (params.coulomb_friction != 0u)
#endif
#ifndef PINS_MOVE
#define PINS_MOVE (params.pins_moving != 0u)
#endif
#ifndef WIND_ENABLED
#define WIND_ENABLED (params.wind_enabled != 0u)
#endif
#ifndef ATTACHMENTS
#define ATTACHMENTS true
#endif
#ifndef SKINNED_MESHES
#define SKINNED_MESHES (params.skin_vertices != 0u)
#endif

int sphere_count() { return COLLIDE_SPHERES ? int(params.sphere_count) : 0; }
int plane_count() { return COLLIDE_PLANES ? int(params.plane_count) : 0; }
int mesh_count() { return COLLIDE_MESHES ? int(params.mesh_count) : 0; }
bool has_colliders() { return sphere_count() + plane_count() + mesh_count() > 0; }
// A collider's motion over this substep: exactly zero where none moves.
vec3 collider_motion(vec3 m) { return COLLIDERS_MOVE ? m : vec3(0.0); }

#endif

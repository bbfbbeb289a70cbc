// Reads the step parameters, rest lengths and colliders; writes positions and probe_uints.
// One invocation does the work. Test fixture for tests/test_gpu_layout.cpp: it declares the
// buffers exactly as the passes do (the parameter block comes from common.glsl itself) and
// copies every member of every struct out, so the compiler keeps them all and the test can
// check that GLSL reads the values C++ wrote.
#include "../../compute/layout.glsl"
#include "../../compute/common.glsl"

// A binding no pass uses: the uvec4 members go out here, so no integer passes through a float.
#define BINDING_PROBE_UINTS 15

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_REST) readonly buffer Rest { RestLengths rest[]; };
layout(std430, binding = BINDING_SPHERES) readonly buffer Spheres { SphereCollider spheres[]; };
layout(std430, binding = BINDING_PLANES) readonly buffer Planes { PlaneCollider planes[]; };
layout(std430, binding = BINDING_PROBE_UINTS) writeonly buffer ProbeUints { uvec4 probe_uints[]; };

void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  pos[0] = params.gravity_mass;
  pos[1] = params.springs;
  pos[2] = params.constraint;
  probe_uints[0] = params.grid;
  probe_uints[1] = params.enabled;
  probe_uints[2] = params.colliders;
  // Element 1 of each array, so a wrong stride shows as well as a wrong offset.
  pos[3] = rest[1].near;
  pos[4] = rest[1].far;
  pos[5] = spheres[1].origin_radius;
  pos[6] = spheres[1].keep;
  pos[7] = planes[1].point;
  pos[8] = planes[1].normal;
}

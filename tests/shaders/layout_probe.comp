// Reads the step parameters, the substep's control, materials and colliders; writes positions and probe_uints.
// One invocation does the work. Test fixture for tests/test_gpu_layout.cpp: it declares the
// buffers exactly as the passes do (the parameter block comes from common.glsl itself) and
// copies every member of every struct out, so the compiler keeps them all and the test can
// check that GLSL reads the values C++ wrote.
#include "../../compute/layout.glsl"
#include "../../compute/common.glsl"

// A binding no pass uses: the step parameters go out here as bits, one uint per scalar.
#define BINDING_PROBE_UINTS 21

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_MATERIALS) readonly buffer Materials { MaterialTexels materials[]; };
layout(std430, binding = BINDING_SPHERES) readonly buffer Spheres { SphereCollider spheres[]; };
layout(std430, binding = BINDING_PLANES) readonly buffer Planes { PlaneCollider planes[]; };
layout(std430, binding = BINDING_MESHES) readonly buffer Meshes { MeshCollider meshes[]; };
layout(std430, binding = BINDING_PROBE_UINTS) writeonly buffer ProbeUints { uint probe_uints[]; };

uint next_uint = 0u;
void put(uint v) { probe_uints[next_uint++] = v; }
void put(float v) { put(floatBitsToUint(v)); }
void put(vec3 v) { put(v.x); put(v.y); put(v.z); }

// Every field of StepParams in declaration order, the list of layout.glsl itself.
#define PUT_FIELD(type, name) put(params.name);
// Then every field of SubstepControl, the same way.
#define PUT_CONTROL_FIELD(type, name) put(control.name);

void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  STEP_PARAMS_FIELDS(PUT_FIELD)
  SUBSTEP_CONTROL_FIELDS(PUT_CONTROL_FIELD)
  // Element 1 of each array, so a wrong stride shows as well as a wrong offset.
  pos[0] = materials[1].stiffness;
  pos[1] = materials[1].keep;
  pos[2] = spheres[1].origin_radius;
  pos[3] = spheres[1].keep;
  pos[4] = planes[1].point;
  pos[5] = planes[1].normal;
  pos[6] = spheres[1].motion;
  pos[7] = planes[1].motion;
  // Never true: keeps the mesh colliders' block in the program, for its stride and offsets.
  if (params.count == 0xffffffffu) pos[0] = meshes[1].material + vec4(meshes[1].dims);
}

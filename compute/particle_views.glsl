// Read-only texel views of the particle, collider and cloth-model buffers (host:
// gl::BufferTexture). The hot passes read through these and write through the storage-buffer
// bindings of the same buffers: a texel fetch is a plain read-only load on a GPU, and on
// llvmpipe it is a vectorised gather, where a storage-buffer read is a bounds-checked loop over
// the lanes, about three times the instructions. Writes made by a previous pass are visible
// after glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); a pass never reads a texel another of its
// own invocations writes.
#ifndef CLOTHSIM_PARTICLE_VIEWS_GLSL
#define CLOTHSIM_PARTICLE_VIEWS_GLSL

#include "shared/springs.glsl"

layout(binding = TEXTURE_POSITIONS) uniform samplerBuffer positions_view;
layout(binding = TEXTURE_DISPLACEMENT) uniform samplerBuffer displacement_view;
layout(binding = TEXTURE_SPRINGS) uniform usamplerBuffer springs_view;
layout(binding = TEXTURE_SPHERES) uniform samplerBuffer spheres_view;
layout(binding = TEXTURE_PLANES) uniform samplerBuffer planes_view;
layout(binding = TEXTURE_CELL_START) uniform usamplerBuffer cell_start_view;
layout(binding = TEXTURE_SORTED_POSITIONS) uniform samplerBuffer sorted_positions_view;
layout(binding = TEXTURE_GATHER_START) uniform usamplerBuffer gather_start_view;
layout(binding = TEXTURE_GATHER) uniform usamplerBuffer gather_view;
layout(binding = TEXTURE_PARTICLES) uniform samplerBuffer particles_view;
layout(binding = TEXTURE_MATERIALS) uniform samplerBuffer materials_view;
layout(binding = TEXTURE_CORNER_START) uniform usamplerBuffer corner_start_view;
layout(binding = TEXTURE_CORNER_TRIANGLES) uniform usamplerBuffer corner_triangles_view;
layout(binding = TEXTURE_TRIANGLES) uniform usamplerBuffer triangles_view;
layout(binding = TEXTURE_REST_POSITIONS) uniform samplerBuffer rest_positions_view;
layout(binding = TEXTURE_MESHES) uniform samplerBuffer meshes_view;
layout(binding = TEXTURE_MESHES_INT) uniform isamplerBuffer meshes_int_view;
layout(binding = TEXTURE_SDF) uniform samplerBuffer sdf_view;
layout(binding = TEXTURE_ATTACHMENTS) uniform samplerBuffer attachments_view;
layout(binding = TEXTURE_SKINNED) uniform samplerBuffer skinned_view;
layout(binding = TEXTURE_SKIN_INDICES) uniform usamplerBuffer skin_indices_view;

vec4 position_of(int i) { return texelFetch(positions_view, i); }
vec4 displacement_of(int i) { return texelFetch(displacement_view, i); }
float mass_of(int i) { return texelFetch(particles_view, i).x; }
int material_index_of(int i) { return int(texelFetch(particles_view, i).y); }

// Particle i's attachment (Constants::attach; docs/model.md, "Attachments"): false if it has
// none; else xyz of `rel` its start position less its collider's start origin, w the stiffness,
// and `origin` the collider's origin at the substep's end (Constants::attached_origin).
bool attachment_of(int i, out vec4 rel, out vec3 origin) {
  origin = vec3(0.0);
  rel = texelFetch(attachments_view, i);
  if (rel.w == 0.0) return false;
  vec4 particle = texelFetch(particles_view, i);
  uint code = uint(particle.z), k = code >> 2;
  if ((code & 3u) == 1u) origin = texelFetch(spheres_view, int(k) * SPHERE_TEXELS).xyz;
  else if ((code & 3u) == 2u) origin = texelFetch(planes_view, int(k) * PLANE_TEXELS).xyz;
  else if (texelFetch(meshes_int_view, int(k) * MESH_TEXELS + 8).y > 0)  // skinned: its vertex (particle.w), skinned
    origin = texelFetch(skinned_view, int(particle.w)).xyz;
  else origin = vec3(texelFetch(meshes_view, int(k) * MESH_TEXELS).w, texelFetch(meshes_view, int(k) * MESH_TEXELS + 1).w,
                     texelFetch(meshes_view, int(k) * MESH_TEXELS + 2).w);
  return true;
}

// One cloth's material (MaterialTexels in layout.glsl, MaterialC in host/core/reference/reference.hpp).
struct Material {
  vec4 stiffness;  // ks, ks_bending, start_ks, w unused
  vec4 keep;       // keep_velocity, then 1 per enabled spring type
  vec4 moduli;     // a material's C11, C22, compression ratio, G (0: none)
};
Material material(int m) {
  return Material(texelFetch(materials_view, MATERIAL_TEXELS * m), texelFetch(materials_view, MATERIAL_TEXELS * m + 1),
                  texelFetch(materials_view, MATERIAL_TEXELS * m + 2));
}
Material material_of(int i) { return material(material_index_of(i)); }
// Both from one fetch of particle i's texel (a pass that needs its mass and its material).
Material material_and_mass_of(int i, out float mass) {
  vec4 particle = texelFetch(particles_view, i);
  mass = particle.x;
  return material(int(particle.y));
}
// SpringType::Seam (host/core/cloth/cloth.hpp): always on (its keep has no entry: the || skips the read).
const uint SEAM_SPRING = 3u;
bool type_enabled(Material m, uint type) { return type == SEAM_SPRING || m.keep[1 + int(type)] != 0.0; }
float stiffness(Material m, uint type) { return type == 2u ? m.stiffness.y : m.stiffness.x; }

// Gather entry g of a particle of material `mat` (TEXTURE_GATHER): its other end and type, and
// its rest length and stiffness now, as Constants::rest_of and stiffness_of give them: a seam's
// rest shrinks as it closes and it takes the lower ks of its two cloths. False (nothing else
// read) for a spring of a type its cloth has off.
bool gathered_spring(uint g, Material mat, out int other, out uint type, out float rest, out float k) {
  uvec2 entry = texelFetch(gather_view, int(g)).xy;  // x: the other end | type << 30, y: rest bits
  type = entry.x >> 30;
  other = int(entry.x & 0x3FFFFFFFu);
  rest = uintBitsToFloat(entry.y);
  k = 0.0;
  if (!type_enabled(mat, type)) return false;
  k = stiffness(mat, type);
  if (type == SEAM_SPRING) {
    rest = seam_rest(rest, control.seam_shrink);
    k = min(k, material_of(other).stiffness.x);
  }
  return true;
}

// With a material (ClothModel::membrane, ::bend, ::hinges): particle i's membrane entries are
// the texel pairs [membrane_first(i), membrane_first(i + 1)) of TEXTURE_GATHER, its bending row
// the texels [bend_first(i), bend_first(i + 1)) (two entries each), its hinge entries the texel
// pairs [hinge_first(i), hinge_first(i + 1)); their starts follow the springs' (gpu_state.cpp).
uint material_start(int list, int i) { return texelFetch(gather_start_view, list * (int(particle_count()) + 1) + i).x; }
uint membrane_first(int i) { return material_start(1, i); }
uint bend_first(int i) { return material_start(2, i); }
uint hinge_first(int i) { return material_start(3, i); }

// The triangles around particle i are corner entries [corners_first(i), corners_first(i + 1)),
// ascending: the order compute_normals and compute_wind_forces gather in on both backends.
uint corners_first(int i) { return texelFetch(corner_start_view, i).x; }
ivec3 corner_triangle(uint k) {
  return ivec3(texelFetch(triangles_view, int(texelFetch(corner_triangles_view, int(k)).x)).xyz);
}

#endif

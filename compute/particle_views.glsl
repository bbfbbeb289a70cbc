// Read-only texel views of the particle and collider buffers (host: gl::BufferTexture). The
// hot passes read through these and write through the storage-buffer bindings of the same
// buffers: a texel fetch is a plain read-only load on a GPU, and on llvmpipe it is a
// vectorised gather, where a storage-buffer read is a bounds-checked loop over the lanes,
// about three times the instructions. Writes made by a previous pass are visible after
// glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); a pass never reads a texel another of its
// own invocations writes.
#ifndef CLOTHSIM_PARTICLE_VIEWS_GLSL
#define CLOTHSIM_PARTICLE_VIEWS_GLSL

layout(binding = TEXTURE_POSITIONS) uniform samplerBuffer positions_view;
layout(binding = TEXTURE_DISPLACEMENT) uniform samplerBuffer displacement_view;
layout(binding = TEXTURE_REST) uniform samplerBuffer rest_view;
layout(binding = TEXTURE_SPHERES) uniform samplerBuffer spheres_view;
layout(binding = TEXTURE_PLANES) uniform samplerBuffer planes_view;
layout(binding = TEXTURE_CELL_START) uniform usamplerBuffer cell_start_view;
layout(binding = TEXTURE_SORTED_POSITIONS) uniform samplerBuffer sorted_positions_view;
layout(binding = TEXTURE_TETHERS) uniform samplerBuffer tethers_view;

vec4 position_of(int i) { return texelFetch(positions_view, i); }
vec4 displacement_of(int i) { return texelFetch(displacement_view, i); }
// RestLengths is two vec4s: near (directions 0-3), far (directions 4-5).
float rest_length(int i, int direction) {
  return texelFetch(rest_view, REST_TEXELS * i + (direction >> 2))[direction & 3];
}

#endif

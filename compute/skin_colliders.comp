// Linear blend skinning of the skinned mesh colliders (docs/model.md, "Skinned and animated
// colliders"): every skinned vertex at the substep's end and at its start, from its bind-pose
// position and its bones' matrices at both times (the palette, set by the host for the substep).
// First pass of every substep of a scene with a skinned collider (its row in
// host/gpu/pass_table.hpp). CPU twin: skin_colliders in host/core/reference/reference_skinning.cpp.
// One invocation per skinned vertex; writes its own two texels (the first also the summed
// moves of compute/nearest.glsl).
#include "layout.glsl"
#include "common.glsl"
#include "shared/skinning.glsl"
#include "nearest.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_SKINNED) buffer Skinned { vec4 skinned[]; };
layout(binding = TEXTURE_SKINNED) uniform samplerBuffer skinned_view;
layout(binding = TEXTURE_SKIN_INDICES) uniform usamplerBuffer skin_indices_view;
layout(binding = TEXTURE_SKIN_WEIGHTS) uniform samplerBuffer skin_weights_view;
layout(binding = TEXTURE_SKIN_PALETTE) uniform samplerBuffer skin_palette_view;

void main() {
  uint i = gl_GlobalInvocationID.x, n = params.skin_vertices;
  if (i == 0u) {  // the last substep's largest move into the sum (nearest.glsl); this one's from 0
    nearest[skin_moved_at()] = floatBitsToUint(skin_moved());
    nearest[skin_motion_at()] = 0u;
  }
  if (i >= n) return;
  vec3 r = texelFetch(skinned_view, int(2u * n + i)).xyz;  // the bind pose's section
  uvec4 bones = texelFetch(skin_indices_view, int(i));
  vec4 w = texelFetch(skin_weights_view, int(i));
  vec3 now = vec3(0.0), start = vec3(0.0);
  for (int k = 0; k < 4; ++k) {
    int s = 3 * int(bones[k]), e = 3 * int(params.skin_palette + bones[k]);
    now = add_bone(now, w[k], texelFetch(skin_palette_view, e), texelFetch(skin_palette_view, e + 1),
                   texelFetch(skin_palette_view, e + 2), r);
    start = add_bone(start, w[k], texelFetch(skin_palette_view, s), texelFetch(skin_palette_view, s + 1),
                     texelFetch(skin_palette_view, s + 2), r);
  }
  skinned[i] = vec4(now, 0.0);
  skinned[n + i] = vec4(start, 0.0);
}

// The skinned mesh colliders' boxes (docs/model.md, "Skinned and animated colliders"): each
// cluster's box around its triangles where skin_colliders put them, each group's around its
// clusters and each super-group's around its groups, the three-level tree a mass's search for
// its nearest triangle descends (compute/collide_meshes.glsl). After skin_colliders (its row in
// host/gpu/pass_table.hpp). CPU twin: fit_collider_boxes in
// host/core/reference/reference_skinning.cpp. One invocation per super-group; writes its
// groups' clusters', its groups' and its own boxes, and in its own box's w the largest move of
// its vertices over the substep (the searches' reach: skinned_reach); the first of each
// workgroup then writes the root box around the workgroup's super-groups (w: their largest move).
#include "layout.glsl"
#include "common.glsl"
#include "shared/skinning.glsl"
#include "skin_tree.glsl"
#include "nearest.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_SKINNED) buffer Skinned { vec4 skinned[]; };
layout(binding = TEXTURE_SKIN_INDICES) uniform usamplerBuffer skin_indices_view;

shared vec4 lo_of[WORKGROUP_SIZE];  // each super-group's box (w: its largest move), for the root's
shared vec3 hi_of[WORKGROUP_SIZE];

// Super-group s's boxes (and those below it): its own, with its vertices' largest move.
void fit_super_group(SkinTree tree, uint s, out vec3 slo, out vec3 shi, out float motion) {
  uvec4 super_group = texelFetch(skin_indices_view, int(tree.supers_at + s));
  slo = vec3(0.0);
  shi = vec3(0.0);
  motion = 0.0;
  for (uint g = super_group.x; g < super_group.x + super_group.y; ++g) {
    uvec4 group = texelFetch(skin_indices_view, int(tree.groups_at + g));
    vec3 glo = vec3(0.0), ghi = vec3(0.0);
    for (uint k = group.x; k < group.x + group.y; ++k) {
      uvec4 cluster = texelFetch(skin_indices_view, int(tree.clusters_at + k));
      vec3 lo = vec3(0.0), hi = vec3(0.0);
      for (uint t = cluster.x; t < cluster.x + cluster.y; ++t) {
        uvec4 tri = texelFetch(skin_indices_view, int(params.skin_vertices + t));
        for (int corner = 0; corner < 3; ++corner) {
          // skin_colliders wrote them, the substep's end and its start (its barrier: SHADER_STORAGE)
          vec3 q = skinned[tri[corner]].xyz, start = skinned[params.skin_vertices + tri[corner]].xyz;
          widen_box(lo, hi, q, q, t == cluster.x && corner == 0);
          motion = max(motion, length3(q - start));
        }
      }
      skinned[tree.boxes + 2u * k] = vec4(lo, 0.0);
      skinned[tree.boxes + 2u * k + 1u] = vec4(hi, 0.0);
      widen_box(glo, ghi, lo, hi, k == group.x);
    }
    skinned[tree.group_boxes + 2u * g] = vec4(glo, 0.0);
    skinned[tree.group_boxes + 2u * g + 1u] = vec4(ghi, 0.0);
    widen_box(slo, shi, glo, ghi, g == super_group.x);
  }
  skinned[tree.super_boxes + 2u * s] = vec4(slo, motion);
  skinned[tree.super_boxes + 2u * s + 1u] = vec4(shi, 0.0);
}

void main() {
  uint s = gl_GlobalInvocationID.x, local = gl_LocalInvocationID.x;
  SkinTree tree = skin_tree();
  if (s < params.skin_supers) {
    vec3 slo, shi;
    float motion;
    fit_super_group(tree, s, slo, shi, motion);
    lo_of[local] = vec4(slo, motion);
    hi_of[local] = shi;
  }
  // The first invocation reads every other's box: their shared writes first.
  memoryBarrierShared();
  barrier();
  if (local != 0u) return;
  uint root = gl_WorkGroupID.x, count = min(uint(WORKGROUP_SIZE), params.skin_supers - root * uint(WORKGROUP_SIZE));
  vec3 lo = vec3(0.0), hi = vec3(0.0);
  float motion = 0.0;
  for (uint i = 0u; i < count; ++i) {
    widen_box(lo, hi, lo_of[i].xyz, hi_of[i], i == 0u);
    motion = max(motion, lo_of[i].w);
  }
  skinned[tree.root_boxes + 2u * root] = vec4(lo, motion);
  atomicMax(nearest[skin_motion_at()], floatBitsToUint(motion));  // the substep's largest (nearest.glsl)
  skinned[tree.root_boxes + 2u * root + 1u] = vec4(hi, 0.0);
}

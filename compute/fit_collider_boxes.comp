// The skinned mesh colliders' boxes (docs/model.md, "Skinned and animated colliders"): each
// cluster's box around its triangles where skin_colliders put them, and each group's around its
// clusters, the two-level tree a mass's search for its nearest triangle descends
// (compute/collide_meshes.glsl). After skin_colliders (its row in host/gpu/pass_table.hpp). CPU
// twin: fit_collider_boxes in host/core/reference/reference_skinning.cpp. One invocation per
// group; writes its clusters' and its own boxes.
#include "layout.glsl"
#include "common.glsl"
#include "shared/skinning.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_SKINNED) buffer Skinned { vec4 skinned[]; };
layout(binding = TEXTURE_SKIN_INDICES) uniform usamplerBuffer skin_indices_view;

void main() {
  uint g = gl_GlobalInvocationID.x;
  if (g >= params.skin_groups) return;
  uint n = params.skin_vertices, boxes = 3u * n, group_boxes = boxes + 2u * params.skin_clusters;
  uint clusters_at = n + params.skin_triangles, groups_at = clusters_at + params.skin_clusters;
  uvec4 group = texelFetch(skin_indices_view, int(groups_at + g));
  vec3 glo = vec3(0.0), ghi = vec3(0.0);
  for (uint k = group.x; k < group.x + group.y; ++k) {
    uvec4 cluster = texelFetch(skin_indices_view, int(clusters_at + k));
    vec3 lo = vec3(0.0), hi = vec3(0.0);
    for (uint t = cluster.x; t < cluster.x + cluster.y; ++t) {
      uvec4 tri = texelFetch(skin_indices_view, int(n + t));
      for (int corner = 0; corner < 3; ++corner) {
        vec3 q = skinned[tri[corner]].xyz;  // skin_colliders wrote them (its barrier: SHADER_STORAGE)
        bool first = t == cluster.x && corner == 0;
        lo = first ? q : min3(lo, q);
        hi = first ? q : max3(hi, q);
      }
    }
    skinned[boxes + 2u * k] = vec4(lo, 0.0);
    skinned[boxes + 2u * k + 1u] = vec4(hi, 0.0);
    glo = k == group.x ? lo : min3(glo, lo);
    ghi = k == group.x ? hi : max3(ghi, hi);
  }
  skinned[group_boxes + 2u * g] = vec4(glo, 0.0);
  skinned[group_boxes + 2u * g + 1u] = vec4(ghi, 0.0);
}

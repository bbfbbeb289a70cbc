// Where the skinned colliders' tree of boxes lies (docs/model.md, "Skinned and animated
// colliders"; four levels: clusters of triangles, groups of clusters, super-groups of groups,
// and a root box per WORKGROUP_SIZE super-groups): read by fit_collider_boxes, which refits it,
// and by the searches that descend it (collide_meshes.glsl). The CPU twins index
// Control::skinned and SkinLists the same way (host/core/reference/reference_skinning.cpp).
#ifndef CLOTHSIM_SKIN_TREE_GLSL
#define CLOTHSIM_SKIN_TREE_GLSL

// The sections of TEXTURE_SKINNED and TEXTURE_SKIN_INDICES the tree's levels start at.
struct SkinTree {
  uint boxes, group_boxes, super_boxes, root_boxes;  // cluster, group, super-group and root boxes (TEXTURE_SKINNED)
  uint clusters_at, groups_at, supers_at;  // their lists (TEXTURE_SKIN_INDICES)
};
SkinTree skin_tree() {
  SkinTree t;
  t.boxes = 3u * params.skin_vertices;
  t.group_boxes = t.boxes + 2u * params.skin_clusters;
  t.super_boxes = t.group_boxes + 2u * params.skin_groups;
  t.root_boxes = t.super_boxes + 2u * params.skin_supers;  // one per WORKGROUP_SIZE super-groups
  t.clusters_at = params.skin_vertices + params.skin_triangles;
  t.groups_at = t.clusters_at + params.skin_clusters;
  t.supers_at = t.groups_at + params.skin_groups;
  return t;
}

#endif

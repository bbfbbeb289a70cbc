// The reference's skinned mesh colliders (docs/model.md, "Skinned and animated colliders"): the
// fixed lists and clusters (make_skins), the palette at a substep (set_skin_palette), the
// skinning passes' twins (skin_colliders, fit_collider_boxes) and a mass's frame (skinned_mesh_at). The formulas are
// compute/shared/skinning.glsl's; compute/skin_colliders.comp and compute/collide_meshes.glsl
// run the same loops on the GPU.
#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

#include "colliders/mesh_collider.hpp"
#include "scene/motion.hpp"
#include "reference/reference.hpp"
#include "reference/reference_detail.hpp"
#include "reference/reference_skinning.hpp"
#include "../../../compute/shared/skinning.glsl"

namespace clothsim {
namespace {

// Orders triangles [begin, end) (their centroids in `at`, one list per pose) so that every run of
// 8, 128 and 1024 (a cluster, a group, a super-group: kClusterTriangles and the levels above) is
// a compact part of the body in every pose: split in two across the longest side of the
// centroids' boxes, of whichever pose it is longest in, at the multiple of the largest level
// below the count nearest its half, each side ordered the same way (a k-d tree's leaves in
// order). The poses are the bind pose and kTreePoses of the animation (tree_poses): in the
// bind pose alone a hand resting on a thigh shared their clusters, whose boxes then spanned a
// metre once the arm rose, and half the cloth was within reach of one. (Morton order, used
// before, put far parts of a limb's surface in one group: the curve's jumps.)
void order_for_tree(std::vector<uint32_t>::iterator begin, std::vector<uint32_t>::iterator end,
                    const std::vector<std::vector<glm::dvec3>>& at) {
  const size_t n = size_t(end - begin);
  if (n <= kClusterTriangles) return;
  size_t level = kClusterTriangles;
  for (size_t up : {kClusterTriangles * kGroupClusters, kClusterTriangles * kGroupClusters * kSuperGroups})
    if (up < n) level = up;
  const size_t half = std::clamp<size_t>((n / 2 + level / 2) / level * level, level, n - 1);
  size_t pose = 0;
  int axis = 0;
  double longest = -1;
  for (size_t j = 0; j < at.size(); ++j) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (auto t = begin; t != end; ++t) lo = glm::min(lo, at[j][*t]), hi = glm::max(hi, at[j][*t]);
    for (int a = 0; a < 3; ++a)
      if (hi[a] - lo[a] > longest) longest = hi[a] - lo[a], pose = j, axis = a;
  }
  const std::vector<glm::dvec3>& key = at[pose];
  std::nth_element(begin, begin + std::ptrdiff_t(half), end, [&](uint32_t a, uint32_t b) {
    return key[a][axis] < key[b][axis] || (key[a][axis] == key[b][axis] && a < b);
  });
  order_for_tree(begin, begin + std::ptrdiff_t(half), at);
  order_for_tree(begin + std::ptrdiff_t(half), end, at);
}

// A palette entry's three rows, as add_bone reads them: row r is (L[0][r], L[1][r], L[2][r], t[r])
// for the entry's linear part L and move t.
std::array<glm::dvec4, 3> bone_rows(const glm::dmat3& linear, const glm::dvec3& move) {
  std::array<glm::dvec4, 3> rows;
  for (int r = 0; r < 3; ++r) rows[size_t(r)] = glm::dvec4(linear[0][r], linear[1][r], linear[2][r], move[r]);
  return rows;
}

// The triangles' centroids in the bind pose and at kTreePoses times spread over the animation,
// in the collider's units before its rotation and origin (which move every pose alike).
std::vector<std::vector<glm::dvec3>> tree_poses(const ColliderMesh& mesh, const Skin& skin, double scale) {
  const auto& tris = mesh.surface.triangles;
  const auto& ps = mesh.surface.positions;
  const double rate = skin.time_scale * skin.ticks_per_second;
  const int poses = skin.duration_ticks > 0 && rate > 0 ? kTreePoses : 0;
  std::vector<std::vector<glm::dvec3>> at(size_t(1 + poses));
  for (int j = 0; j <= poses; ++j) {
    std::vector<glm::dvec3> v(ps);
    if (j > 0) {  // linear blend skinning as skin_colliders does it (add_bone), in double
      std::vector<std::array<glm::dvec4, 3>> rows;
      for (const glm::dmat4& b : skin.palette_at(skin.duration_ticks * (j - 1) / poses / rate))
        rows.push_back(bone_rows(glm::dmat3(b), scale * glm::dvec3(b[3])));
      for (size_t i = 0; i < ps.size(); ++i) {
        glm::dvec3 sum(0);
        for (int k = 0; k < kBonesPerVertex; ++k) {
          const std::array<glm::dvec4, 3>& b = rows[skin.bones[i][k]];
          sum = shared::add_bone(sum, skin.weights[i][k], b[0], b[1], b[2], ps[i]);
        }
        v[i] = sum;
      }
    }
    for (const glm::uvec3& t : tris) at[size_t(j)].push_back((v[t.x] + v[t.y] + v[t.z]) / 3.0);
  }
  return at;
}

}  // namespace

template <class R>
void make_skins(const Scene& scene, const std::vector<std::shared_ptr<const ColliderMesh>>& loaded, Constants<R>& c) {
  std::vector<Vec4<R>> rest;
  uint32_t palette = 0;
  for (size_t k = 0; k < loaded.size(); ++k) {
    const ColliderMesh& mesh = *loaded[k];
    if (!mesh.skin) continue;
    const Skin& skin = *mesh.skin;
    const MeshColliderParams& p = scene.meshes[k];
    const uint32_t first_vertex = uint32_t(rest.size());
    for (size_t v = 0; v < mesh.surface.positions.size(); ++v) {
      rest.push_back(Vec4<R>(Vec3<R>(mesh.surface.positions[v]), R(0)));
      c.skin.bones.push_back(skin.bones[v] + glm::uvec4(palette));
      c.skin.weights.push_back(Vec4<R>(skin.weights[v]));
    }
    // Triangles near one another in the bind pose make a cluster, clusters near one another a
    // group, groups a super-group (order_for_tree), whose boxes fit_collider_boxes refits
    // every substep.
    const auto& tris = mesh.surface.triangles;
    std::vector<uint32_t> order(tris.size());
    std::iota(order.begin(), order.end(), 0u);
    order_for_tree(order.begin(), order.end(), tree_poses(mesh, skin, p.scale));
    const size_t first_cluster = c.skin.clusters.size(), first_group = c.skin.groups.size();
    for (size_t i = 0; i < order.size(); i += kClusterTriangles)
      c.skin.clusters.push_back({uint32_t(c.skin.triangles.size() + i), uint32_t(std::min<size_t>(kClusterTriangles, order.size() - i)), 0, 0});
    for (size_t i = first_cluster; i < c.skin.clusters.size(); i += kGroupClusters)
      c.skin.groups.push_back({uint32_t(i), uint32_t(std::min<size_t>(kGroupClusters, c.skin.clusters.size() - i)), 0, 0});
    const size_t first_super = c.skin.supers.size();
    for (size_t i = first_group; i < c.skin.groups.size(); i += kSuperGroups)
      c.skin.supers.push_back({uint32_t(i), uint32_t(std::min<size_t>(kSuperGroups, c.skin.groups.size() - i)), 0, 0});
    // w: its super-group (the reach its search uses): the lists above are full runs but the last.
    const size_t per_super = size_t(kClusterTriangles) * kGroupClusters * kSuperGroups;
    for (size_t i = 0; i < order.size(); ++i)
      c.skin.triangles.push_back(glm::uvec4(tris[order[i]] + glm::uvec3(first_vertex), uint32_t(first_super + i / per_super)));
    c.control.meshes[k].skin = glm::ivec4(int(first_super), int(c.skin.supers.size() - first_super),
                                          int(c.timeline.skins.size()), 0);
    c.timeline.skins.push_back({mesh.skin, k, palette, p.scale, collider_rotation(p)});
    palette += uint32_t(skin.palette_node.size());
  }
  if (rest.empty()) return;
  c.skin_vertices = uint32_t(rest.size());
  c.skin_triangles = uint32_t(c.skin.triangles.size());
  c.skin_clusters = uint32_t(c.skin.clusters.size());
  c.skin_groups = uint32_t(c.skin.groups.size());
  c.skin_supers = uint32_t(c.skin.supers.size());
  c.skin_palette = palette;
  c.skin_meshes = uint32_t(c.timeline.skins.size());
  c.control.palette.assign(size_t(6) * palette, Vec4<R>(0));
  const size_t roots = (c.skin.supers.size() + WORKGROUP_SIZE - 1) / WORKGROUP_SIZE;
  c.control.skinned.assign(3 * rest.size() + 2 * (c.skin.clusters.size() + c.skin.groups.size() + c.skin.supers.size() + roots),
                           Vec4<R>(0));
  std::copy(rest.begin(), rest.end(), c.control.skinned.begin() + 2 * std::ptrdiff_t(rest.size()));
}

template <class R> uint32_t nearest_skinned_vertex(const Constants<R>& c, size_t mesh, const glm::dvec3& p) {
  const glm::ivec4 skin = c.control.meshes[mesh].skin;
  // The collider's vertices are those of its groups' clusters' triangles.
  uint32_t best = 0;
  double best_d2 = std::numeric_limits<double>::max();
  const uint32_t first = c.skin.supers[size_t(skin.x)].x, last = c.skin.supers[size_t(skin.x + skin.y - 1)].x +
                                                                  c.skin.supers[size_t(skin.x + skin.y - 1)].y;
  for (uint32_t g = first; g < last; ++g)
    for (uint32_t k = c.skin.groups[size_t(g)].x; k < c.skin.groups[size_t(g)].x + c.skin.groups[size_t(g)].y; ++k)
      for (uint32_t t = c.skin.clusters[k].x; t < c.skin.clusters[k].x + c.skin.clusters[k].y; ++t)
        for (int corner = 0; corner < 3; ++corner) {
          const uint32_t v = c.skin.triangles[t][corner];
          const glm::dvec3 e = glm::dvec3(Vec3<R>(c.control.skinned[v])) - p;
          const double d2 = glm::dot(e, e);
          if (d2 < best_d2 || (d2 == best_d2 && v < best)) best_d2 = d2, best = v;
        }
  return best;
}

template <class R> void set_skin_palette(Constants<R>& c, double start, double end_time) {
  const Timeline& tl = c.timeline;
  for (const SkinnedTimeline& s : tl.skins) {
    for (int end = 0; end < 2; ++end) {
      const double at = end ? end_time : start;
      const glm::dvec3 origin = keyed_at(tl.meshes[s.mesh], tl.mesh_origins[s.mesh], at);
      const std::vector<glm::dmat4> bones = s.skin->palette_at(at);
      for (size_t j = 0; j < bones.size(); ++j) {
        // origin + rotation (scale B r_file): the linear part rotation B3, the translation
        // origin + rotation (scale b), on the scaled rest positions.
        const std::array<glm::dvec4, 3> rows = bone_rows(s.rotation * glm::dmat3(bones[j]),
                                                         origin + s.rotation * (s.scale * glm::dvec3(bones[j][3])));
        const size_t base = 3 * (size_t(end) * c.skin_palette + s.palette_first + j);
        for (size_t r = 0; r < 3; ++r) c.control.palette[base + r] = Vec4<R>(rows[r]);
      }
    }
  }
}

template <class R> void skin_colliders(Control<R>& control, const Constants<R>& c) {
  const size_t n = c.skin_vertices, palette = c.skin_palette;
  const std::vector<Vec4<R>>& pal = control.palette;
  for (size_t i = 0; i < n; ++i) {
    const Vec3<R> r(control.skinned[2 * n + i]);
    const glm::uvec4 b = c.skin.bones[i];
    const Vec4<R> w = c.skin.weights[i];
    Vec3<R> now(0), start(0);
    for (int k = 0; k < kBonesPerVertex; ++k) {
      const size_t s = 3 * size_t(b[k]), e = 3 * (palette + b[k]);
      now = shared::add_bone(now, w[k], pal[e], pal[e + 1], pal[e + 2], r);
      start = shared::add_bone(start, w[k], pal[s], pal[s + 1], pal[s + 2], r);
    }
    control.skinned[i] = Vec4<R>(now, R(0));
    control.skinned[n + i] = Vec4<R>(start, R(0));
  }
}

template <class R> void fit_collider_boxes(Control<R>& control, const Constants<R>& c) {
  const size_t n = c.skin_vertices, boxes = 3 * n, groups = boxes + 2 * c.skin.clusters.size();
  const size_t supers = groups + 2 * c.skin.groups.size();
  std::vector<Vec4<R>>& sk = control.skinned;
  auto store = [&](size_t at, const Vec3<R>& lo, const Vec3<R>& hi) {
    sk[at] = Vec4<R>(lo, R(0));
    sk[at + 1] = Vec4<R>(hi, R(0));
  };
  // As one invocation of fit_collider_boxes.comp per super-group does it.
  for (size_t s = 0; s < c.skin.supers.size(); ++s) {
    const glm::uvec4 su = c.skin.supers[s];
    Vec3<R> slo(0), shi(0);  // as the shader: the first box sets them
    R motion(0);  // the largest move of its vertices over the substep (skinned_reach)
    for (uint32_t g = su.x; g < su.x + su.y; ++g) {
      const glm::uvec4 gr = c.skin.groups[g];
      Vec3<R> glo(0), ghi(0);
      for (uint32_t k = gr.x; k < gr.x + gr.y; ++k) {
        const glm::uvec4 cl = c.skin.clusters[k];
        Vec3<R> lo(0), hi(0);
        for (uint32_t t = cl.x; t < cl.x + cl.y; ++t)
          for (int corner = 0; corner < 3; ++corner) {
            const Vec3<R> q(sk[c.skin.triangles[t][corner]]), start(sk[n + c.skin.triangles[t][corner]]);
            shared::widen_box(lo, hi, q, q, t == cl.x && corner == 0);
            motion = std::max(motion, length3(q - start));
          }
        store(boxes + 2 * k, lo, hi);
        shared::widen_box(glo, ghi, lo, hi, k == gr.x);
      }
      store(groups + 2 * g, glo, ghi);
      shared::widen_box(slo, shi, glo, ghi, g == su.x);
    }
    store(supers + 2 * s, slo, shi);
    sk[supers + 2 * s].w = motion;
  }
  // A root box per WORKGROUP_SIZE super-groups (w: their largest move), as each workgroup's first
  // invocation fits it.
  const size_t roots = supers + 2 * c.skin.supers.size();
  for (size_t first = 0; first < c.skin.supers.size(); first += WORKGROUP_SIZE) {
    Vec3<R> lo(0), hi(0);
    R motion(0);
    for (size_t s = first; s < std::min<size_t>(first + WORKGROUP_SIZE, c.skin.supers.size()); ++s) {
      shared::widen_box(lo, hi, Vec3<R>(sk[supers + 2 * s]), Vec3<R>(sk[supers + 2 * s + 1]), s == first);
      motion = std::max(motion, sk[supers + 2 * s].w);
    }
    store(roots + 2 * (first / WORKGROUP_SIZE), lo, hi);
    sk[roots + 2 * (first / WORKGROUP_SIZE)].w = motion;
  }
}

namespace {

// The least (distance, index) triangle of skinned collider m within its reach of x (each
// super-group's: skinned_reach, its vertices' largest move in its box's w), or kNoParticle;
// started from *cached (when given and set) and kept there.
template <class R>
uint32_t nearest_skinned_triangle(const Constants<R>& c, const MeshColliderT<R>& m, const Vec3<R>& x, const Vec3<R>& d,
                                  uint32_t* cached) {
  const std::vector<Vec4<R>>& sk = c.control.skinned;
  const size_t n = c.skin_vertices, boxes = 3 * n, group_boxes = boxes + 2 * c.skin.clusters.size();
  const size_t super_boxes = group_boxes + 2 * c.skin.groups.size();
  const R base = shared::skinned_reach_base(m.material.y, d);
  auto reach2_of_box = [&](size_t box) {  // a super-group's or a root's (its w: the largest move under it)
    const R reach = shared::skinned_reach(base, sk[box].w, m.grid.w);
    return reach * reach;
  };
  auto reach2_of = [&](size_t s) { return reach2_of_box(super_boxes + 2 * s); };
  R best(0);  // (none found yet: the reach bounds alone)
  uint32_t found = kNoParticle;
  const auto visit = [&](uint32_t t, R reach2) {
    const glm::uvec4 tri = c.skin.triangles[t];
    Vec3<R> b3;
    const Vec3<R> q = shared::closest_on_triangle(x, Vec3<R>(sk[tri.x]), Vec3<R>(sk[tri.y]), Vec3<R>(sk[tri.z]), b3);
    const R d2 = dot3(x - q, x - q);
    if (shared::nearer(d2, t, reach2, best, found)) best = d2, found = t;
  };
  // The last search's: a bound to start from, within its own super-group's reach (its w).
  if (cached && *cached != kNoParticle) visit(*cached, reach2_of(c.skin.triangles[*cached].w));
  auto beyond = [&](size_t box, R reach2) {
    const R bound = found == kNoParticle ? reach2 : std::min(best, reach2);
    return shared::box_beyond(shared::box_distance2(x, Vec3<R>(sk[box]), Vec3<R>(sk[box + 1])), bound);
  };
  auto search_super_group = [&](size_t s) {
    const R reach2 = reach2_of(s);
    if (beyond(super_boxes + 2 * s, reach2)) return;
    const glm::uvec4 su = c.skin.supers[s];
    for (uint32_t g = su.x; g < su.x + su.y; ++g) {
      if (beyond(group_boxes + 2 * size_t(g), reach2)) continue;
      const glm::uvec4 gr = c.skin.groups[size_t(g)];
      for (uint32_t k = gr.x; k < gr.x + gr.y; ++k) {
        if (beyond(boxes + 2 * size_t(k), reach2)) continue;
        const glm::uvec4 cl = c.skin.clusters[k];
        for (uint32_t t = cl.x; t < cl.x + cl.y; ++t) visit(t, reach2);
      }
    }
  };
  // The root boxes, WORKGROUP_SIZE super-groups each (fit_collider_boxes), then their super-groups.
  const size_t root_boxes = super_boxes + 2 * c.skin.supers.size(), first = size_t(m.skin.x), last = first + size_t(m.skin.y);
  for (size_t r = first / WORKGROUP_SIZE; r <= (last - 1) / WORKGROUP_SIZE; ++r) {
    if (beyond(root_boxes + 2 * r, reach2_of_box(root_boxes + 2 * r))) continue;
    for (size_t s = std::max(first, r * WORKGROUP_SIZE); s < std::min(last, (r + 1) * WORKGROUP_SIZE); ++s)
      search_super_group(s);
  }
  if (cached) *cached = found;
  return found;
}

}  // namespace

template <class R>
bool skinned_mesh_at(const Constants<R>& c, const MeshColliderT<R>& m, const Vec3<R>& x, const Vec3<R>& d,
                     MeshColliderT<R>& frame, uint32_t* slots, bool search) {
  const std::vector<Vec4<R>>& sk = c.control.skinned;
  const size_t n = c.skin_vertices;
  uint32_t* cached = slots ? &slots[m.skin.z] : nullptr;
  const uint32_t found = search || !cached ? nearest_skinned_triangle(c, m, x, d, cached) : *cached;
  if (found == kNoParticle) return false;
  const glm::uvec4 tri = c.skin.triangles[size_t(found)];
  auto at = [&](size_t section, uint32_t v) { return Vec3<R>(sk[section * n + v]); };
  Vec3<R> bary, r0, r1, r2, origin, motion;
  shared::closest_on_triangle(x, at(0, tri.x), at(0, tri.y), at(0, tri.z), bary);
  shared::skinned_frame(at(0, tri.x), at(0, tri.y), at(0, tri.z), at(1, tri.x), at(1, tri.y), at(1, tri.z), at(2, tri.x),
                        at(2, tri.y), at(2, tri.z), bary, x, d, r0, r1, r2, origin, motion);
  frame = m;
  frame.row0 = Vec4<R>(r0, origin.x);
  frame.row1 = Vec4<R>(r1, origin.y);
  frame.row2 = Vec4<R>(r2, origin.z);
  frame.motion = Vec4<R>(motion, m.motion.w);
  return true;
}

#define CLOTHSIM_INSTANTIATE(R)                                                                                        \
  template void make_skins<R>(const Scene&, const std::vector<std::shared_ptr<const ColliderMesh>>&, Constants<R>&); \
  template void set_skin_palette<R>(Constants<R>&, double, double);                                                          \
  template uint32_t nearest_skinned_vertex<R>(const Constants<R>&, size_t, const glm::dvec3&);                     \
  template void skin_colliders<R>(Control<R>&, const Constants<R>&);                                                \
  template void fit_collider_boxes<R>(Control<R>&, const Constants<R>&);                                            \
  template bool skinned_mesh_at<R>(const Constants<R>&, const MeshColliderT<R>&, const Vec3<R>&, const Vec3<R>&,     \
                                   MeshColliderT<R>&, uint32_t*, bool);
CLOTHSIM_INSTANTIATE(float)
CLOTHSIM_INSTANTIATE(double)

}  // namespace clothsim

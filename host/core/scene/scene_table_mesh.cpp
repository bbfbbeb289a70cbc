// The mesh colliders' rows of the scene parameter table (scene_table.cpp says what a row is):
// the file and its placement, the field, and what moves its vertices (bones, a point cache).
#include "scene/scene_table.hpp"
#include "scene/scene_table_detail.hpp"

namespace clothsim {
namespace {

using namespace table_detail;

const Param<MeshColliderParams> kMeshCollider[] = {
    row<&MeshColliderParams::file>({.key = "file", .required = true, .expected = "a path to a mesh file",
                                    .meaning = "a mesh file (OBJ, PLY, glTF, STL, ...), relative to the scene file; "
                                               "closed for an inside, open for a shell of `thickness`",
                                    .widget = kReadOnly}),
    row<&MeshColliderParams::scale>({.key = "scale", .lo = 1e-9, .expected = "a scale > 0",
                                     .meaning = "the file's coordinates are multiplied by this (metres per unit)",
                                     .widget = kReadOnly}),
    row<&MeshColliderParams::origin>({.key = "origin", .unit = "m", .meaning = "where the file's origin is placed, last"}),
    row<&MeshColliderParams::rotation_axis>({.key = "rotation_axis", .meaning = "non-zero; made unit length on loading",
                                             .widget = kReadOnly, .after_read = normalise_axis}),
    row<&MeshColliderParams::rotation_degrees>({.key = "rotation_degrees", .unit = "°",
                                                .meaning = "rotation about rotation_axis (right-handed), after the scale",
                                                .widget = kReadOnly}),
    row<&MeshColliderParams::friction>({.key = "friction", .lo = 0, .hi = 1,
                                        .expected = "a friction coefficient in [0, 1]", .meaning = kFriction.meaning}),
    row<&MeshColliderParams::motion>({.key = "motion", .meaning = "keyframed origin, in place of `origin` (the mesh "
                                                                  "translates); friction acts relative to it"}),
    row<&MeshColliderParams::voxel_size>({.key = "voxel_size", .lo = 0, .expected = "a spacing >= 0 (metres)",
                                          .unit = "m",
                                          .meaning = "node spacing of the signed distance field; 0: the mesh's longest "
                                                     "extent / 128 (a field is at most 256 MiB)",
                                          .widget = kReadOnly}),
    row<&MeshColliderParams::thickness>({.key = "thickness", .lo = 0, .expected = "a thickness >= 0 (metres)",
                                         .unit = "m", .meaning = "masses are kept this far outside the surface"}),
    row<&MeshColliderParams::animation>({.key = "animation", .expected = "an animation's name or index",
                                         .meaning = "a skinned collider: the file's bones move its vertices through "
                                                    "this animation (its name, or its index from 0); absent: rigid",
                                         .widget = kReadOnly, .index_or_name = true}),
    row<&MeshColliderParams::time_scale>({.key = "time_scale", .lo = 0, .hi = 1e6,
                                          .expected = "a time scale in [0, 1e6]",
                                          .meaning = "animation seconds per scene second (0 holds the first pose)",
                                          .widget = kReadOnly}),
    row<&MeshColliderParams::loop>({.key = "loop", .meaning = "the animation (or cache) starts over at its end; false: "
                                                             "it holds its last pose", .widget = kReadOnly}),
    row<&MeshColliderParams::point_cache>({.key = "point_cache", .expected = "a path to a PC2 file",
                                           .meaning = "a deforming collider: a PC2 point cache of `file`'s vertices "
                                                      "(Blender's Mesh Cache), relative to the scene file",
                                           .widget = kReadOnly}),
    row<&MeshColliderParams::sequence>({.key = "sequence", .expected = "a path to a folder of OBJ files",
                                        .meaning = "a deforming collider: a folder of OBJ files of `file`'s vertices, "
                                                   "one a frame in name order (--export-colliders writes one)",
                                        .widget = kReadOnly}),
    row<&MeshColliderParams::cache_frames_per_sec>({.key = "cache_frames_per_sec", .lo = 0, .hi = 1e6,
                                                    .expected = "frames per second in [0, 1e6]", .unit = "1/s",
                                                    .meaning = "the point cache's or sequence's frame rate; 0: the "
                                                               "scene's frames_per_sec", .widget = kReadOnly}),
};

}  // namespace

template <> std::span<const Param<MeshColliderParams>> param_rows<MeshColliderParams>() { return kMeshCollider; }

}  // namespace clothsim

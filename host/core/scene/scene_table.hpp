// The rows of the scene structs (defined in scene_table.cpp, the one place that lists the
// scene parameters) and the table-driven JSON reader and writer built on them.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "scene/param_table.hpp"
#include "scene/scene.hpp"

namespace clothsim {

template <> std::span<const Param<Scene>> param_rows<Scene>();
template <> std::span<const Param<ClothParams>> param_rows<ClothParams>();
template <> std::span<const Param<SphereParams>> param_rows<SphereParams>();
template <> std::span<const Param<MeshColliderParams>> param_rows<MeshColliderParams>();
template <> std::span<const Param<PlaneParams>> param_rows<PlaneParams>();
template <> std::span<const Param<SimulationParams>> param_rows<SimulationParams>();
template <> std::span<const Param<MotionParams>> param_rows<MotionParams>();
template <> std::span<const Param<WindParams>> param_rows<WindParams>();
template <> std::span<const Param<GustParams>> param_rows<GustParams>();
template <> std::span<const Param<BoxParams>> param_rows<BoxParams>();
template <> std::span<const Param<AttachmentParams>> param_rows<AttachmentParams>();
template <> std::span<const Param<SeamParams>> param_rows<SeamParams>();
template <> std::span<const Param<MaterialParams>> param_rows<MaterialParams>();

// Reads the rows of `object` from `j`, the value at key path `path` ("" for the top level) of
// the file `source`: strict (unknown keys, wrong types, values out of range are a SceneError
// naming source and key path); keys left out keep the struct's defaults.
void read_object(const nlohmann::json& j, const std::string& source, const std::string& path, ObjectRef& object);
// The rows of `object` as a JSON object (optional objects left out, lists always written).
nlohmann::json write_object(ObjectRef& object);

template <class S>
void read_params(const nlohmann::json& j, const std::string& source, const std::string& path, S& s) {
  detail::PlainObject<S> ref(s);
  read_object(j, source, path, ref);
}
template <class S>
nlohmann::json write_params(S s) {  // a copy: visitors take members by reference
  detail::PlainObject<S> ref(s);
  return write_object(ref);
}

}  // namespace clothsim

// A skinned, animated collider for the tests (test_skinned_colliders.cpp and its GPU twin): a
// glTF 2.0 file written here, a closed box of half-size `half` whose eight vertices all follow
// one bone, and that bone's animation, keys in seconds (translations or rotations). Assimp reads
// it as a character file: a mesh, a skin of one joint, one animation.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace clothsim::test {

struct BoneKeys {
  std::vector<float> times;                 // s
  std::vector<glm::vec3> translations;      // one per time, or empty
  std::vector<glm::quat> rotations;         // one per time, or empty
};

// Writes DIR/NAME.gltf and DIR/NAME.bin; returns the .gltf's path.
inline std::string write_skinned_box(const std::filesystem::path& dir, const std::string& name, float half,
                                     const BoneKeys& keys) {
  std::vector<uint8_t> bin;
  auto put = [&](const void* data, size_t bytes) {
    const size_t at = bin.size();
    bin.resize(at + bytes);
    std::memcpy(bin.data() + at, data, bytes);
    while (bin.size() % 4) bin.push_back(0);
    return at;
  };
  std::vector<float> positions;
  for (int i = 0; i < 8; ++i)
    for (int a = 0; a < 3; ++a) positions.push_back((i >> a) & 1 ? half : -half);
  // Twelve triangles, counter-clockwise seen from outside (vertex i: bit 0 x, bit 1 y, bit 2 z).
  const uint16_t tris[] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                           2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  const uint8_t joints[8 * 4] = {};  // every vertex: joint 0
  std::vector<float> weights;
  for (int i = 0; i < 8; ++i) weights.insert(weights.end(), {1.f, 0.f, 0.f, 0.f});
  const size_t p_at = put(positions.data(), positions.size() * 4), t_at = put(tris, sizeof tris);
  const size_t j_at = put(joints, sizeof joints), w_at = put(weights.data(), weights.size() * 4);
  const size_t time_at = put(keys.times.data(), keys.times.size() * 4);
  const bool rotate = !keys.rotations.empty();
  std::vector<float> values;
  for (const glm::vec3& v : keys.translations) values.insert(values.end(), {v.x, v.y, v.z});
  for (const glm::quat& q : keys.rotations) values.insert(values.end(), {q.x, q.y, q.z, q.w});
  const size_t value_at = put(values.data(), values.size() * 4);
  // The inverse bind matrix, the identity (Assimp 5.2 needs it written out: it crashes on a skin without).
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const size_t ibm_at = put(identity, sizeof identity);
  std::ofstream(dir / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
  const size_t n = keys.times.size();
  const std::string gltf = fmt::format(R"({{
  "asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [{{"name": "box", "mesh": 0, "skin": 0}}, {{"name": "bone"}}],
  "skins": [{{"joints": [1], "inverseBindMatrices": 6}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3}}, "indices": 1}}]}}],
  "animations": [{{"name": "move", "channels": [{{"sampler": 0, "target": {{"node": 1, "path": "{}"}}}}],
                   "samplers": [{{"input": 4, "output": 5, "interpolation": "LINEAR"}}]}}],
  "buffers": [{{"byteLength": {}, "uri": "{}.bin"}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": {}, "byteLength": 96}}, {{"buffer": 0, "byteOffset": {}, "byteLength": 72}},
                  {{"buffer": 0, "byteOffset": {}, "byteLength": 32}}, {{"buffer": 0, "byteOffset": {}, "byteLength": 128}},
                  {{"buffer": 0, "byteOffset": {}, "byteLength": {}}}, {{"buffer": 0, "byteOffset": {}, "byteLength": {}}},
                  {{"buffer": 0, "byteOffset": {}, "byteLength": 64}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [{}, {}, {}], "max": [{}, {}, {}]}},
    {{"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}},
    {{"bufferView": 2, "componentType": 5121, "count": 8, "type": "VEC4"}},
    {{"bufferView": 3, "componentType": 5126, "count": 8, "type": "VEC4"}},
    {{"bufferView": 4, "componentType": 5126, "count": {}, "type": "SCALAR", "min": [{}], "max": [{}]}},
    {{"bufferView": 5, "componentType": 5126, "count": {}, "type": "{}"}},
    {{"bufferView": 6, "componentType": 5126, "count": 1, "type": "MAT4"}}]
}})",
                                       rotate ? "rotation" : "translation", bin.size(), name, p_at, t_at, j_at, w_at,
                                       time_at, n * 4, value_at, values.size() * 4, ibm_at, -half, -half, -half, half, half, half,
                                       n, keys.times.front(), keys.times.back(), n, rotate ? "VEC4" : "VEC3");
  const std::filesystem::path out = dir / (name + ".gltf");
  std::ofstream(out) << gltf;
  return out.string();
}

}  // namespace clothsim::test

// Bones, weights and one animation of a skinned collider's file, read through Assimp, and the
// bones' matrices at a time (skin.hpp).
#include "colliders/skin.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>

#include <assimp/scene.h>
#include <fmt/format.h>

#include "io/point_cache.hpp"
#include "io/input_file.hpp"
#include "scene/scene.hpp"

namespace clothsim {
namespace {

glm::dmat4 to_glm(const aiMatrix4x4& m) {
  glm::dmat4 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = m[r][c];  // row major to glm's columns
  return out;
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The animation `name` (or an index written in digits) of the file, or a SceneError naming those it has.
const aiAnimation& find_animation(const aiScene& scene, const std::string& name, const std::string& what) {
  std::string names;
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
    if (scene.mAnimations[a]->mName.C_Str() == name) return *scene.mAnimations[a];
    names += fmt::format("{}{} \"{}\"", a ? ", " : "", a, scene.mAnimations[a]->mName.C_Str());
  }
  unsigned index = 0;
  const char* end = name.data() + name.size();
  if (auto r = std::from_chars(name.data(), end, index); r.ec == std::errc() && r.ptr == end && index < scene.mNumAnimations)
    return *scene.mAnimations[index];
  if (scene.mNumAnimations == 0) throw SceneError(fmt::format("{}: the file has no animations", what));
  throw SceneError(fmt::format("{}: no animation \"{}\"; expected the name or the index of one of: {}", what, name, names));
}

// Keys held before the first and after the last, linear (spherical for rotations) between.
template <class T, class Mix> T sample(const std::vector<std::pair<double, T>>& keys, double tick, Mix mix) {
  if (tick <= keys.front().first) return keys.front().second;
  if (tick >= keys.back().first) return keys.back().second;
  const auto next = std::upper_bound(keys.begin(), keys.end(), tick, [](double t, const auto& k) { return t < k.first; });
  const auto prev = next - 1;
  const double span = next->first - prev->first;
  return span > 0 ? mix(prev->second, next->second, (tick - prev->first) / span) : next->second;
}

}  // namespace

double Skin::tick_at(double seconds) const {
  const double tick = seconds * time_scale * ticks_per_second;
  if (!(duration_ticks > 0)) return 0;
  if (loop) return tick - duration_ticks * std::floor(tick / duration_ticks);
  return std::clamp(tick, 0.0, duration_ticks);
}

std::vector<glm::dmat4> Skin::palette_at(double seconds) const {
  const double tick = tick_at(seconds);
  if (!frames.empty()) {  // a point cache: vertex v from its rest position to where the frames put it
    const size_t at = std::min(size_t(tick), frames.size() - 1), next = std::min(at + 1, frames.size() - 1);
    const double f = tick - double(at);
    std::vector<glm::dmat4> out(rest.size(), glm::dmat4(1.0));
    for (size_t v = 0; v < rest.size(); ++v) out[v][3] = glm::dvec4(frames[at][v] + (frames[next][v] - frames[at][v]) * f - rest[v], 1.0);
    return out;
  }
  std::vector<glm::dmat4> global(parent.size());
  for (size_t n = 0; n < parent.size(); ++n) {
    glm::dmat4 here = local[n];
    if (channel[n] >= 0) {
      const Channel& ch = channels[size_t(channel[n])];
      const auto lerp = [](const glm::dvec3& a, const glm::dvec3& b, double f) { return a + (b - a) * f; };
      const auto slerp = [](const glm::dquat& a, const glm::dquat& b, double f) {
        return glm::slerp(a, glm::dot(a, b) < 0 ? -b : b, f);  // the shorter way round
      };
      const glm::dvec3 t = ch.positions.empty() ? glm::dvec3(here[3]) : sample(ch.positions, tick, lerp);
      const glm::dquat r = ch.rotations.empty() ? glm::dquat(1, 0, 0, 0) : glm::normalize(sample(ch.rotations, tick, slerp));
      const glm::dvec3 s = ch.scalings.empty() ? glm::dvec3(1.0) : sample(ch.scalings, tick, lerp);
      // T R S, as Assimp composes a channel's keys.
      here = glm::dmat4(glm::mat3_cast(r));
      for (int c = 0; c < 3; ++c) here[c] *= s[c];
      here[3] = glm::dvec4(t, 1.0);
    }
    global[n] = parent[n] >= 0 ? global[size_t(parent[n])] * here : here;
  }
  std::vector<glm::dmat4> out(palette_node.size());
  for (size_t j = 0; j < out.size(); ++j) out[j] = global[size_t(palette_node[j])] * palette_bind[j];
  return out;
}

namespace {

// The frames as a skin: one palette entry per vertex, the frames spanning (frames - 1) / fps seconds.
Skin cache_skin(const std::vector<glm::dvec3>& rest, std::vector<std::vector<glm::dvec3>> frames, double fps) {
  Skin skin;
  skin.frames = std::move(frames);
  skin.rest = rest;
  skin.ticks_per_second = fps;
  skin.duration_ticks = double(skin.frames.size() - 1);
  for (uint32_t v = 0; v < rest.size(); ++v) {
    skin.bones.push_back({v, 0, 0, 0});
    skin.weights.push_back({1, 0, 0, 0});
  }
  skin.palette_node.assign(rest.size(), -1);
  skin.palette_bind.assign(rest.size(), glm::dmat4(1.0));
  return skin;
}

// At most this many positions in a cache held in memory (3 doubles each: 2.4 GB).
constexpr size_t kMaxCachePositions = size_t(100) << 20;

}  // namespace

Skin read_point_cache(const std::vector<glm::dvec3>& rest, const std::filesystem::path& pc2, double fps,
                      const std::string& what) {
  std::vector<std::vector<glm::dvec3>> frames;
  try {
    const Pc2Header h = read_pc2_header(pc2.string());
    if (size_t(h.points) != rest.size())
      throw SceneError(fmt::format("{}: {} has {} points a sample; expected the mesh's {} vertices", what,
                                   printable(pc2.string()), h.points, rest.size()));
    if (h.samples < 1) throw SceneError(fmt::format("{}: {} has no samples", what, printable(pc2.string())));
    if (double(h.samples) * double(h.points) > double(kMaxCachePositions))
      throw SceneError(fmt::format("{}: {} holds {} positions, more than the {} a collider may", what,
                                   printable(pc2.string()), double(h.samples) * h.points, kMaxCachePositions));
    // One stream for every sample (the header's read checked the file: a regular file, its counts).
    std::ifstream in(pc2, std::ios::binary);
    const uint64_t size = std::filesystem::file_size(pc2);
    for (int k = 0; k < h.samples; ++k) {
      const std::vector<glm::vec3> sample = read_pc2_sample(in, size, pc2.string(), k);
      frames.emplace_back(sample.begin(), sample.end());
    }
  } catch (const Pc2Error& e) {
    throw SceneError(fmt::format("{}: {}", what, e.what()));
  }
  return cache_skin(rest, std::move(frames), fps);
}

Skin read_obj_sequence(const std::vector<glm::dvec3>& rest, const std::filesystem::path& folder, double fps,
                       const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw SceneError(fmt::format("{}: {} is not a folder; expected a folder of OBJ files, one a frame", what,
                                 printable(folder.string())));
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".obj") files.push_back(e.path());
  }
  if (ec || files.empty())
    throw SceneError(fmt::format("{}: {} has no .obj files (expected one a frame)", what, printable(folder.string())));
  if (double(files.size()) * double(rest.size()) > double(kMaxCachePositions))
    throw SceneError(fmt::format("{}: {} frames of {} vertices are more than the {} positions a collider may hold", what,
                                 files.size(), rest.size(), kMaxCachePositions));
  std::sort(files.begin(), files.end());
  std::vector<std::vector<glm::dvec3>> frames;
  for (const fs::path& f : files) {
    PolyMesh frame = load_mesh(f, what, /*manifold=*/false);
    if (frame.positions.size() != rest.size())
      throw SceneError(fmt::format("{}: {} has {} vertices; expected the mesh's {}", what, printable(f.string()),
                                   frame.positions.size(), rest.size()));
    frames.push_back(std::move(frame.positions));
  }
  return cache_skin(rest, std::move(frames), fps);
}

Skin read_skin(const aiScene& scene, std::span<const MeshUse> uses, size_t vertices, const std::string& animation,
               const std::string& what) {
  Skin skin;
  const aiAnimation& anim = find_animation(scene, animation, what);
  skin.animation = anim.mName.C_Str();
  skin.ticks_per_second = anim.mTicksPerSecond > 0 ? anim.mTicksPerSecond : 25.0;  // Assimp's default
  skin.duration_ticks = std::isfinite(anim.mDuration) && anim.mDuration > 0 ? anim.mDuration : 0.0;

  // The node tree, parents first (an explicit stack: a hostile file's tree can be deep).
  std::map<std::string, int> by_name;
  std::map<const aiNode*, int> index;
  std::vector<std::pair<const aiNode*, int>> stack;
  if (scene.mRootNode) stack.emplace_back(scene.mRootNode, -1);
  while (!stack.empty()) {
    auto [node, up] = stack.back();
    stack.pop_back();
    const int n = int(skin.parent.size());
    skin.parent.push_back(up);
    skin.local.push_back(to_glm(node->mTransformation));
    skin.channel.push_back(-1);
    index[node] = n;
    by_name.try_emplace(node->mName.C_Str(), n);  // the first of a repeated name
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], n);
  }
  for (unsigned c = 0; c < anim.mNumChannels; ++c) {
    const aiNodeAnim* ch = anim.mChannels[c];
    auto it = by_name.find(ch->mNodeName.C_Str());
    if (it == by_name.end() || skin.channel[size_t(it->second)] >= 0) continue;  // a channel for no node
    Skin::Channel out;
    const std::string key = fmt::format("{}: animation \"{}\", channel \"{}\"", what, skin.animation, ch->mNodeName.C_Str());
    for (unsigned k = 0; k < ch->mNumPositionKeys; ++k) {
      const aiVectorKey& v = ch->mPositionKeys[k];
      out.positions.push_back({v.mTime, {v.mValue.x, v.mValue.y, v.mValue.z}});
    }
    for (unsigned k = 0; k < ch->mNumScalingKeys; ++k) {
      const aiVectorKey& v = ch->mScalingKeys[k];
      out.scalings.push_back({v.mTime, {v.mValue.x, v.mValue.y, v.mValue.z}});
    }
    for (unsigned k = 0; k < ch->mNumRotationKeys; ++k) {
      const aiQuatKey& q = ch->mRotationKeys[k];
      out.rotations.push_back({q.mTime, glm::dquat(q.mValue.w, q.mValue.x, q.mValue.y, q.mValue.z)});
      if (!std::isfinite(q.mTime) || !finite({q.mValue.x, q.mValue.y, q.mValue.z}) || !std::isfinite(q.mValue.w))
        throw SceneError(fmt::format("{}: a rotation key is not finite", key));
    }
    for (const auto* keys : {&out.positions, &out.scalings})
      for (const auto& [t, v] : *keys)
        if (!std::isfinite(t) || !finite(v)) throw SceneError(fmt::format("{}: a key is not finite", key));
    // Keys in time order (Assimp's are; a file's may not be): a stable sort keeps equal times in order.
    auto by_time = [](const auto& a, const auto& b) { return a.first < b.first; };
    std::stable_sort(out.positions.begin(), out.positions.end(), by_time);
    std::stable_sort(out.scalings.begin(), out.scalings.end(), by_time);
    std::stable_sort(out.rotations.begin(), out.rotations.end(), by_time);
    skin.channel[size_t(it->second)] = int(skin.channels.size());
    skin.channels.push_back(std::move(out));
  }

  // The palette, and each vertex's four heaviest weights. A vertex of a mesh with bones that
  // none of them weighs follows the mesh's node, as a mesh without bones does.
  std::vector<std::vector<std::pair<double, uint32_t>>> influences(vertices);
  std::vector<int> node_entry(skin.parent.size(), -1);
  auto entry = [&](int node, const glm::dmat4& bind) {
    skin.palette_node.push_back(node);
    skin.palette_bind.push_back(bind);
    return uint32_t(skin.palette_node.size() - 1);
  };
  for (const MeshUse& use : uses) {
    const glm::dmat4 unplace = glm::inverse(use.transform);
    const int node = index.at(use.node);
    for (unsigned b = 0; b < use.mesh->mNumBones; ++b) {
      const aiBone& bone = *use.mesh->mBones[b];
      auto it = by_name.find(bone.mName.C_Str());
      if (it == by_name.end()) continue;  // a bone no node moves: its vertices follow the mesh's node
      const uint32_t j = entry(it->second, to_glm(bone.mOffsetMatrix) * unplace);
      for (unsigned w = 0; w < bone.mNumWeights; ++w) {
        const aiVertexWeight& vw = bone.mWeights[w];
        if (vw.mVertexId >= use.mesh->mNumVertices)
          throw SceneError(fmt::format("{}: bone \"{}\" weighs vertex {}, which its mesh does not have", what,
                                       bone.mName.C_Str(), vw.mVertexId));
        if (vw.mWeight > 0 && std::isfinite(vw.mWeight))
          influences[use.particle[vw.mVertexId]].push_back({vw.mWeight, j});
      }
    }
    // The node's own entry for the vertices no bone weighs (a welded vertex keeps its first bones).
    for (unsigned v = 0; v < use.mesh->mNumVertices; ++v) {
      auto& inf = influences[use.particle[v]];
      if (!inf.empty()) continue;
      if (node_entry[size_t(node)] < 0) node_entry[size_t(node)] = int(entry(node, unplace));
      inf.push_back({1.0, uint32_t(node_entry[size_t(node)])});
    }
  }
  skin.bones.assign(vertices, glm::uvec4(0));
  skin.weights.assign(vertices, glm::dvec4(0.0));
  for (size_t v = 0; v < vertices; ++v) {
    auto& inf = influences[v];
    if (inf.empty()) {  // a vertex no face uses: still, it must follow something
      if (skin.palette_node.empty()) entry(0, glm::inverse(skin.local[0]));
      inf.push_back({1.0, 0u});
    }
    std::stable_sort(inf.begin(), inf.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    double sum = 0;
    for (size_t k = 0; k < inf.size() && k < size_t(kBonesPerVertex); ++k) sum += inf[k].first;
    for (size_t k = 0; k < inf.size() && k < size_t(kBonesPerVertex); ++k) {
      skin.bones[v][int(k)] = inf[k].second;
      skin.weights[v][int(k)] = inf[k].first / sum;
    }
  }
  return skin;
}

}  // namespace clothsim

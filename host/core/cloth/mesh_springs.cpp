// build_mesh_springs: the edge table of the mesh (faces per edge, edges per vertex, both in
// discovery order), then three walks over the faces, one per spring type (mesh_springs.hpp).
#include "cloth/mesh_springs.hpp"

#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace clothsim {
namespace {

constexpr uint32_t kNone = UINT32_MAX;

struct Edge {
  uint32_t a, b;                        // as first met: corner k to corner k+1 of its first face
  uint32_t face[2] = {kNone, kNone};    // the (at most two) faces holding it, in face order
  bool quad = false;                    // in at least one quad
};

uint64_t pair_key(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a; }

struct EdgeTable {
  std::vector<Edge> edges;
  std::vector<std::array<uint32_t, 4>> face_edges;  // edge id of each face's edge k
  std::vector<uint32_t> first, incident;             // CSR: edges at vertex v, in id order

  explicit EdgeTable(const PolyMesh& mesh) {
    const size_t n = mesh.positions.size();
    std::unordered_map<uint64_t, uint32_t> id;
    id.reserve(mesh.faces.size() * 2);
    face_edges.resize(mesh.faces.size());
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& face = mesh.faces[f];
      if (face.size() != 3 && face.size() != 4)
        throw std::invalid_argument("build_mesh_springs: face " + std::to_string(f) + " has " +
                                    std::to_string(face.size()) + " corners (3 or 4 expected)");
      for (size_t k = 0; k < face.size(); ++k) {
        const uint32_t a = face[k], b = face[(k + 1) % face.size()];
        if (a >= n || b >= n || a == b)
          throw std::invalid_argument("build_mesh_springs: face " + std::to_string(f) +
                                      " has a repeated index or one beyond the particles");
        auto [it, added] = id.try_emplace(pair_key(a, b), uint32_t(edges.size()));
        if (added) edges.push_back({a, b});
        Edge& e = edges[it->second];
        if (e.face[0] == kNone) e.face[0] = uint32_t(f);
        else if (e.face[1] == kNone) e.face[1] = uint32_t(f);
        else
          throw std::invalid_argument("build_mesh_springs: the edge " + std::to_string(a) + "-" + std::to_string(b) +
                                      " is in more than two faces");
        e.quad = e.quad || face.size() == 4;
        face_edges[f][k] = it->second;
      }
    }
    first.assign(n + 1, 0);
    for (const Edge& e : edges) ++first[e.a + 1], ++first[e.b + 1];
    for (size_t v = 0; v < n; ++v) first[v + 1] += first[v];
    incident.resize(first[n]);
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (uint32_t i = 0; i < edges.size(); ++i) incident[fill[edges[i].a]++] = i, incident[fill[edges[i].b]++] = i;
  }

  bool share_face(uint32_t e1, uint32_t e2) const {
    for (uint32_t f1 : edges[e1].face)
      for (uint32_t f2 : edges[e2].face)
        if (f1 != kNone && f1 == f2) return true;
    return false;
  }
};

// Appends (a, b) unless the unordered pair is already in any list.
struct SpringSink {
  std::unordered_set<uint64_t> taken;
  void add(std::vector<std::array<uint32_t, 2>>& list, uint32_t a, uint32_t b) {
    if (a != b && taken.insert(pair_key(a, b)).second) list.push_back({a, b});
  }
};

}  // namespace

MeshSprings build_mesh_springs(const PolyMesh& mesh) {
  const EdgeTable table(mesh);
  MeshSprings out;
  SpringSink sink;
  sink.taken.reserve(table.edges.size() * 3);

  for (const auto& face : mesh.faces)
    for (size_t k = 0; k < face.size(); ++k) sink.add(out.structural, face[k], face[(k + 1) % face.size()]);

  for (const auto& face : mesh.faces)
    if (face.size() == 4) sink.add(out.shearing, face[0], face[2]), sink.add(out.shearing, face[1], face[3]);

  std::vector<bool> visited(table.edges.size(), false);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      const uint32_t e = table.face_edges[f][k];
      if (visited[e]) continue;
      visited[e] = true;
      const Edge& edge = table.edges[e];
      if (edge.quad) {
        // Quads: continue the line (v, a) through a along a quad edge that shares no face with it.
        const uint32_t ends[2][2] = {{face[k], face[(k + 1) % face.size()]}, {face[(k + 1) % face.size()], face[k]}};
        for (const auto& [v, a] : ends)
          for (uint32_t i = table.first[a]; i < table.first[a + 1]; ++i) {
            const uint32_t e2 = table.incident[i];
            if (e2 == e || !table.edges[e2].quad || table.share_face(e, e2)) continue;
            const uint32_t b = table.edges[e2].a == a ? table.edges[e2].b : table.edges[e2].a;
            sink.add(out.bending, v, b);
          }
      }
      // Triangles: across an edge shared by two triangles, opposite vertex to opposite vertex.
      if (face.size() == 3 && edge.face[1] != kNone) {
        const auto& other = mesh.faces[edge.face[0] == f ? edge.face[1] : edge.face[0]];
        if (other.size() != 3) continue;
        uint32_t opposite = kNone;
        for (uint32_t c : other)
          if (c != edge.a && c != edge.b) opposite = c;
        if (opposite != kNone) sink.add(out.bending, face[(k + 2) % 3], opposite);
      }
    }
  }
  return out;
}

}  // namespace clothsim

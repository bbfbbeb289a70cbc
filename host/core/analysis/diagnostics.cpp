#include "analysis/diagnostics.hpp"

#include "colliders/mesh_collider.hpp"
#include "colliders/winding.hpp"
#include "reference/reference_detail.hpp"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <fmt/os.h>
#include <glm/vector_relational.hpp>

#include "scene/motion.hpp"
#include "io/output_file.hpp"


namespace clothsim {
namespace {

glm::dvec3 xyz(const glm::dvec4& v) { return {v.x, v.y, v.z}; }

glm::dvec3 initial_centre(const ClothModel& m) {
  glm::dvec3 c(0);
  for (auto& p : m.initial) c += p;
  return c / double(m.count());
}

// A skinned collider posed at `time`: the clearance (the least signed distance of a mass to its
// triangles, within the field's band; inside negative by the winding number) and the masses
// inside by the winding number of the posed surface.
void skinned_clearance(const ColliderMesh& mesh, const MeshColliderParams& mp, const glm::dvec3& origin, double time,
                       const ClothSnapshot& s, ClothStats& st) {
  SurfaceMesh posed{posed_positions(mesh, mp, origin, time), mesh.surface.triangles};
  const FastWindingNumber winding(posed, 3.0);  // within about 0.01 of the exact sum
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::dvec3& q : posed.positions) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double band = mesh.sdf.band;
  double best = band;
  size_t inside = 0;
  for (auto& p : s.pos) {
    const glm::dvec3 x = xyz(p);
    const bool in = std::abs(winding(x)) > 0.5;
    inside += in;
    // Every triangle, for the masses within the band of the posed surface's box.
    if (glm::any(glm::lessThan(x, lo - band)) || glm::any(glm::greaterThan(x, hi + band))) continue;
    best = std::min(best, (in ? -1.0 : 1.0) * brute_force_distance(posed, x));
  }
  st.mesh_clearance.push_back(best);
  st.mesh_inside.push_back(inside);
}

}  // namespace

ClothStats measure(const Scene& scene, const ClothModel& m, const ClothSnapshot& s, double time) {
  ClothStats st;
  const double dt = scene.dt();
  const auto cloths = scene.cloths();
  const std::vector<double> mass = particle_masses(scene, m);
  for (int i = 0; i < m.count(); ++i) {
    const glm::dvec3 x = xyz(s.pos[i]);
    for (int c = 0; c < 4; ++c) st.finite = st.finite && std::isfinite(s.pos[i][c]) && std::isfinite(s.disp[i][c]);
    const glm::dvec3 v = xyz(s.disp[i]) / dt;
    if (!m.pinned[i]) st.kinetic += 0.5 * mass[i] * glm::dot(v, v);
    st.max_speed = std::max(st.max_speed, glm::length(v));
    st.gravitational -= mass[i] * glm::dot(scene.simulation.gravity, x);
  }
  std::vector<double> ratios;
  ratios.reserve(m.springs.size());
  auto p_ks = [&](uint32_t i) { return cloths.at(m.material[i])->ks; };
  for (const Spring& sp : m.springs) {
    const double len = glm::length(xyz(s.pos[sp.j]) - xyz(s.pos[sp.i]));
    if (sp.type == SpringType::Seam) {  // a sewn pair: its gap (and the energy of a zero-length spring)
      ++st.seam_pairs;
      st.max_seam_gap = std::max(st.max_seam_gap, len);
      st.spring += 0.5 * std::min(p_ks(sp.i), p_ks(sp.j)) * len * len;
      continue;
    }
    st.max_stretch_ratio = std::max(st.max_stretch_ratio, len / sp.rest);
    ratios.push_back(len / sp.rest);
    const ClothParams& p = *cloths.at(sp.material);
    const bool enabled[3] = {p.enable_structural, p.enable_shearing, p.enable_bending};
    if (enabled[int(sp.type)] && !p.material) {  // a material's energy is its triangles' and hinges', not counted here
      const double k = sp.type == SpringType::Bending ? 0.2 * p.ks : p.ks;
      st.spring += 0.5 * k * (len - sp.rest) * (len - sp.rest);
    }
  }
  if (!ratios.empty()) {
    // The nearest-rank percentile: the smallest ratio that at least 99 % of the springs reach.
    const size_t rank = std::min(ratios.size() - 1, size_t(std::ceil(0.99 * double(ratios.size()))) - 1);
    std::nth_element(ratios.begin(), ratios.begin() + std::ptrdiff_t(rank), ratios.end());
    st.p99_stretch_ratio = ratios[rank];
  }
  const glm::dvec3 centre = initial_centre(m);
  // A keyframed collider is where its keys put it at `time`, as the collision passes of the
  // snapshot's last substep saw it (docs/model.md, "Moving scenes").
  for (auto& sp : scene.spheres) {
    const glm::dvec3 origin = keyed_at(sp.motion, sp.origin, time);
    double best = std::numeric_limits<double>::infinity();
    for (auto& p : s.pos) best = std::min(best, glm::length(xyz(p) - origin) - sp.radius);
    st.sphere_clearance.push_back(best);
  }
  for (auto& pl : scene.planes) {
    // The plane's front (the side the cloth started on, where the plane is at t = 0) counts as
    // outside; a plane through the start centre uses +normal.
    const glm::dvec3 start = keyed_at(pl.motion, pl.point, 0.0), point = keyed_at(pl.motion, pl.point, time);
    double side = glm::dot(centre - start, pl.normal) < 0 ? -1.0 : 1.0;
    double best = std::numeric_limits<double>::infinity();
    for (auto& p : s.pos) best = std::min(best, side * glm::dot(xyz(p) - point, pl.normal));
    st.plane_clearance.push_back(best);
  }
  for (size_t k = 0; k < scene.meshes.size(); ++k) {
    // The field's distance (to the surface, not to its offset by thickness), in the mesh's
    // frame; a mass outside the grid is further than the band.
    const MeshColliderParams& mp = scene.meshes[k];
    const std::shared_ptr<const ColliderMesh> mesh = load_collider_mesh(scene, k);
    MeshColliderT<double> mc = make_mesh_collider<double>(mp, mesh->sdf, 0);  // its own field: offset 0
    if (mp.motion) set_mesh_origin(mc, interpolate(mp.motion->keyframes, time));
    if (mesh->skin) {  // posed at `time`: measured on its triangles, not through the bind pose's field
      skinned_clearance(*mesh, mp, mesh_origin(mc), time, s, st);
      continue;
    }
    double best = mesh->sdf.band;
    for (auto& p : s.pos) {
      double phi;
      glm::dvec3 grad;
      if (sample_mesh_at(mc, mesh->sdf.values.data(), xyz(p), phi, grad)) best = std::min(best, phi);
    }
    st.mesh_clearance.push_back(best);
    // Inside by the exact rule, not the field: the generalised winding number of the surface
    // (winding.hpp), which a hole in the mesh or a mass between field nodes cannot fool.
    const FastWindingNumber winding(mesh->surface, 3.0);  // within about 0.01 of the exact sum
    size_t inside = 0;
    for (auto& p : s.pos) inside += std::abs(winding(mesh_local_point(mc, xyz(p)))) > 0.5;
    st.mesh_inside.push_back(inside);
  }
  return st;
}

void write_obj(const std::string& path, const ClothModel& m, const ClothSnapshot& s) {
  // Written under a temporary name beside `path` and renamed once complete (output_file.hpp),
  // so `path` holds the old file or the whole new one, never a part.
  write_text_file(path, [&](std::FILE* f) {
    if (m.is_grid())
      fmt::print(f, "# clothsim cloth, {}x{} particles, row-major\n", m.nw, m.nh);
    else
      fmt::print(f, "# clothsim cloth, {} particles in {} cloth(s), each mesh in its file's vertex order\n", m.count(),
                 m.parts.size());
    for (auto& p : s.pos) fmt::print(f, "v {:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
    for (auto& t : m.uv) fmt::print(f, "vt {:.9g} {:.9g}\n", t.x, t.y);
    for (int i = 0; i < m.count(); ++i) {
      glm::dvec4 n = i < int(s.normal.size()) ? s.normal[i] : glm::dvec4(0, 1, 0, 0);
      fmt::print(f, "vn {:.9g} {:.9g} {:.9g}\n", n.x, n.y, n.z);
    }
    for (auto& t : m.triangles)
      fmt::print(f, "f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  });
}

}  // namespace clothsim

// Newton's method on the springs' potential energy (static_solve.hpp). Independent of the
// solvers on purpose: it shares only the model (springs, masses, pins) and the scene's
// parameters with them, not a line of their update rules.
#include "analysis/static_solve.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <glm/geometric.hpp>

#include "reference/reference.hpp"

namespace clothsim {

namespace {

// The solve needs the springs, the masses and gravity, whatever the scene's solver: its
// constants are made as for the classic one, so a multigrid scene builds no hierarchy it would
// never use (0.4 s at 513²).
Scene as_classic(Scene scene) {
  scene.simulation.solver = Solver::Classic;
  return scene;
}

struct Problem {
  const ClothModel& model;
  Constants<double> c;
  std::vector<int> unknown;  // per particle: its block in the system, -1 when pinned
  int n = 0;                 // free particles

  Problem(const Scene& scene, const ClothModel& m) : model(m), c(make_constants<double>(as_classic(scene), m)) {
    unknown.assign(size_t(m.count()), -1);
    for (int i = 0; i < m.count(); ++i)
      if (!m.pinned[size_t(i)]) unknown[size_t(i)] = n++;
  }

  // The rest state is the sewn one: a seam at zero length, with its two cloths' lower ks.
  static double rest(const Spring& s) { return s.type == SpringType::Seam ? 0.0 : s.rest; }
  double stiffness(const Spring& s) const { return c.stiffness_of(model, s); }

  double energy(const std::vector<glm::dvec3>& x) const {
    double e = 0;
    for (const Spring& s : model.springs) {
      if (!c.enabled(s)) continue;
      const double stretch = glm::length(x[s.j] - x[s.i]) - rest(s);
      e += 0.5 * stiffness(s) * stretch * stretch;
    }
    for (int i = 0; i < model.count(); ++i)
      if (unknown[size_t(i)] >= 0) e -= c.mass[size_t(i)] * glm::dot(c.gravity, x[size_t(i)]);
    return e;
  }

  // The net force on every free mass (minus the gradient), and the largest of its components.
  Eigen::VectorXd force(const std::vector<glm::dvec3>& x, double* largest) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * n);
    auto add = [&](uint32_t i, const glm::dvec3& v) {
      if (const int k = unknown[i]; k >= 0)
        for (int a = 0; a < 3; ++a) f[3 * k + a] += v[a];
    };
    for (int i = 0; i < model.count(); ++i) add(uint32_t(i), c.mass[size_t(i)] * c.gravity);
    for (const Spring& s : model.springs) {
      if (!c.enabled(s)) continue;
      const glm::dvec3 e = x[s.j] - x[s.i];
      const double len = glm::length(e);
      if (!(len > 0)) continue;
      const glm::dvec3 pull = e * (stiffness(s) * (len - rest(s)) / len);
      add(s.i, pull);
      add(s.j, -pull);
    }
    *largest = f.cwiseAbs().maxCoeff();
    return f;
  }

  // The springs' Hessian, each block ks (u u^T + max(0, 1 - L/len) (I - u u^T)): the clamp
  // drops the compressive part, which would make the system indefinite.
  Eigen::SparseMatrix<double> hessian(const std::vector<glm::dvec3>& x) const {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(model.springs.size() * 36);
    auto block = [&](int a, int b, const double k[3][3], double sign) {
      if (a < 0 || b < 0) return;
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) t.emplace_back(3 * a + r, 3 * b + q, sign * k[r][q]);
    };
    for (const Spring& s : model.springs) {
      if (!c.enabled(s)) continue;
      const glm::dvec3 e = x[s.j] - x[s.i];
      const double len = glm::length(e);
      if (!(len > 0)) continue;
      const glm::dvec3 u = e / len;
      const double ks = stiffness(s), lateral = std::max(0.0, 1.0 - rest(s) / len);
      double k[3][3];
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) k[r][q] = ks * (u[r] * u[q] + lateral * ((r == q ? 1.0 : 0.0) - u[r] * u[q]));
      const int a = unknown[s.i], b = unknown[s.j];
      block(a, a, k, 1);
      block(b, b, k, 1);
      block(a, b, k, -1);
      block(b, a, k, -1);
    }
    Eigen::SparseMatrix<double> h(3 * n, 3 * n);
    h.setFromTriplets(t.begin(), t.end());
    return h;
  }
};

}  // namespace

StaticEquilibrium solve_static_equilibrium(const Scene& scene, const ClothModel& model, double tolerance,
                                           int max_iterations) {
  // (A mesh collider and an attachment, whose anchor a collider carries, are colliders too.)
  if (!scene.spheres.empty() || !scene.planes.empty() || !scene.meshes.empty() || scene.wind ||
      scene.simulation.self_collision)
    throw std::invalid_argument("solve_static_equilibrium: only springs, pins and gravity (no colliders, wind or "
                                "self-collision)");
  if (model.has_material())  // its membrane and bending are the fabric sweep's, not this solve's
    throw std::invalid_argument("solve_static_equilibrium: only springs, pins and gravity (cloth.material: a "
                                "material's membrane and bending are not in the static solve)");
  const Problem p(scene, model);
  StaticEquilibrium out;
  out.pos = model.initial;
  // Every particle pinned: the start is the equilibrium, and an empty system is no system for
  // Eigen (it crashed on one). Converged, with no step taken.
  if (p.n == 0) {
    out.converged = true;
    return out;
  }
  double largest = 0;
  Eigen::VectorXd f = p.force(out.pos, &largest);
  double e = p.energy(out.pos);
  // The damping, relative to the largest spring stiffness: large while the flat start has no
  // stiffness across the sheet, shrinking to nothing (plain Newton) as the steps succeed.
  double ks_max = 0;
  for (const auto& m : p.c.materials) ks_max = std::max(ks_max, m.ks);
  double lambda = 1e-2 * ks_max;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::SparseMatrix<double> identity(3 * p.n, 3 * p.n);
  identity.setIdentity();
  for (; out.iterations < max_iterations && largest > tolerance; ++out.iterations) {
    const Eigen::SparseMatrix<double> h = p.hessian(out.pos);
    bool stepped = false;
    for (int tries = 0; tries < 40 && !stepped; ++tries) {
      ldlt.compute(h + lambda * identity);
      if (ldlt.info() != Eigen::Success) {
        lambda *= 10;
        continue;
      }
      const Eigen::VectorXd dx = ldlt.solve(f);
      std::vector<glm::dvec3> next = out.pos;
      for (int i = 0; i < model.count(); ++i)
        if (const int k = p.unknown[size_t(i)]; k >= 0) next[size_t(i)] += glm::dvec3(dx[3 * k], dx[3 * k + 1], dx[3 * k + 2]);
      // Taken if the energy falls, or, where the energy's change is lost to rounding near the
      // minimum, the largest force does.
      const double e_next = p.energy(next);
      double largest_next = 0;
      Eigen::VectorXd f_next = p.force(next, &largest_next);
      if (e_next < e || largest_next < largest) {
        out.pos = std::move(next);
        e = e_next;
        f = std::move(f_next);
        largest = largest_next;
        lambda *= 0.3;
        stepped = true;
      } else {
        lambda *= 10;
      }
    }
    if (!stepped) break;  // no progress at any damping: as converged as doubles allow
  }
  out.residual = largest;
  out.converged = largest <= tolerance;
  return out;
}

}  // namespace clothsim

#include "colliders/winding.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace clothsim {

using glm::dvec3;

namespace {

// f(z) for z in [0, nz), the slices shared among the hardware's threads (each node is its own,
// so the field is the same whatever the thread count).
template <class F> void for_each_slice(int nz, F&& f) {
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::atomic<int> next{0};
  auto work = [&] {
    for (int z; (z = next.fetch_add(1)) < nz;) f(z);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

// f(node, its index) for every node of g, the z slices shared among the threads as above.
template <class F> void for_each_node(const SdfGrid& g, F&& f) {
  for_each_slice(g.dims.z, [&](int z) {
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) f(glm::ivec3(x, y, z), g.index(x, y, z));
  });
}

}  // namespace

// An open mesh's field: negative where the winding number is above 1/2 (in magnitude: either
// winding), so a hole is closed by that level set and a mass cannot slip in through it. Its
// magnitude is the distance to the surface, or to that level set where it is nearer: across a
// hole the nearest triangle is on the rim, and a field of rim distances would put its zero
// between two nodes anywhere in their cell, up to half a node inside the level set (measured:
// a cloth resting on a bowl's hole 5 mm deep in it). Next to a node of the other sign the
// level set is a fraction (|w_a| - 1/2) / (|w_a| - |w_b|) of a node away along that axis, the
// first-order distance, so the field's zero is where w's is.
//
// w is evaluated (FastWindingNumber) at every band node and every node of even x, y and z; a
// node beyond the band takes the sign of the eight even nodes around it when they are all beyond
// the band and agree. That cannot miss an inside pocket: a node beyond the band has no surface
// within 3 nodes, and one of its even corners is within sqrt(3) of it, so on its side. Elsewhere
// (near a hole's level set, at the grid's far edges), and at both ends of every sign change, the
// node is evaluated itself. Wuson at 6 mm: about a third of its 3.27M nodes evaluated; the
// whole field 3.4 s on 2 cores.
void sign_by_winding(const SurfaceMesh& mesh, SdfGrid& g, const std::vector<int32_t>& nearest,
                     const std::vector<double>& dist2) {
  const glm::ivec3 dims = g.dims;
  auto in_grid = [&](const glm::ivec3& p) { return glm::all(glm::greaterThanEqual(p, glm::ivec3(0))) && glm::all(glm::lessThan(p, dims)); };
  auto position = [&](const dvec3& node) { return g.min + node * g.voxel; };
  const FastWindingNumber winding(mesh, kSdfWindingAccuracy);
  std::vector<float> w(g.nodes(), -1.f);  // |w|; -1: not evaluated (its sign taken from its corners)
  std::vector<int8_t> inside(g.nodes(), -1);
  auto evaluate = [&](const glm::ivec3& p, size_t k) {
    w[k] = float(std::abs(winding(position(dvec3(p)))));
    inside[k] = w[k] > 0.5f;
  };
  for_each_node(g, [&](const glm::ivec3& p, size_t k) {
    if (nearest[k] >= 0 || glm::all(glm::equal(p % 2, glm::ivec3(0)))) evaluate(p, k);
  });
  for_each_node(g, [&](const glm::ivec3& p, size_t k) {
    if (inside[k] >= 0) return;
    int agree = -1;  // the corners' common sign, or -2 when they do not all give one
    for (int c = 0; c < 8 && agree != -2; ++c) {
      const glm::ivec3 corner = (p & ~1) + 2 * glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      if (!in_grid(corner)) { agree = -2; break; }
      const size_t ck = g.index(corner.x, corner.y, corner.z);
      if (nearest[ck] >= 0 || (agree >= 0 && inside[ck] != agree)) agree = -2;
      else agree = inside[ck];
    }
    if (agree >= 0) inside[k] = int8_t(agree);
    else evaluate(p, k);
  });
  auto neighbours = [&](const glm::ivec3& p, auto&& f) {
    for (int axis = 0; axis < 3; ++axis)
      for (int dir : {-1, 1}) {
        glm::ivec3 o = p;
        o[axis] += dir;
        if (in_grid(o)) f(o, g.index(o.x, o.y, o.z));
      }
  };
  auto at_sign_change = [&](const glm::ivec3& p, size_t k) {
    bool change = false;
    neighbours(p, [&](const glm::ivec3&, size_t ok) { change = change || inside[ok] != inside[k]; });
    return change;
  };
  // Both ends of every sign change evaluated again, to within about 0.002 of the exact sum (beta
  // 3; tests), and signed by that: beta 1.5's errors of up to 0.07 put a hole's level set a node
  // off, and where the level set lies between two nodes comes from their values. A node whose
  // sign this changes may make a new change beside it: repeated until none does.
  const FastWindingNumber accurate(mesh, 3.0);
  std::vector<uint8_t> refined(g.nodes(), 0), due(g.nodes(), 0);
  for (bool flipped = true; flipped;) {
    for_each_node(g, [&](const glm::ivec3& p, size_t k) { due[k] = !refined[k] && at_sign_change(p, k); });
    std::atomic<bool> any{false};
    for_each_node(g, [&](const glm::ivec3& p, size_t k) {
      if (!due[k]) return;
      w[k] = float(std::abs(accurate(position(dvec3(p)))));
      refined[k] = 1;
      if (int8_t(w[k] > 0.5f) != inside[k]) {
        inside[k] = int8_t(w[k] > 0.5f);
        any = true;
      }
    });
    flipped = any;
  }
  // Where |w| = 1/2 between node k (at 0) and its neighbour ok (at 1) of the other sign: the
  // root of the parabola through both and the midpoint, w being curved on the scale of a node
  // (a straight line put it 1 to 3 mm off across a bowl's 35 cm hole at 1 cm nodes).
  auto crossing = [&](size_t k, size_t ok, const glm::ivec3& p, const glm::ivec3& o) {
    const double a = double(w[k]) - 0.5, b = double(w[ok]) - 0.5;  // opposite signs (both refined)
    const double m = std::abs(accurate(position((dvec3(p) + dvec3(o)) * 0.5))) - 0.5;
    const double c1 = -3 * a + 4 * m - b, c2 = 2 * a - 4 * m + 2 * b;  // a + c1 t + c2 t^2
    const double linear = a / (a - b);
    if (std::abs(c2) < 1e-12) return linear;
    const double disc = c1 * c1 - 4 * c2 * a;
    if (disc < 0) return linear;
    for (double t : {(-c1 - std::sqrt(disc)) / (2 * c2), (-c1 + std::sqrt(disc)) / (2 * c2)})
      if (t >= 0 && t <= 1) return t;
    return linear;
  };
  std::vector<double> d(g.nodes());
  for_each_node(g, [&](const glm::ivec3& p, size_t k) {
    d[k] = nearest[k] >= 0 ? std::sqrt(dist2[k]) : g.band;
    neighbours(p, [&](const glm::ivec3& o, size_t ok) {
      if (inside[ok] != inside[k]) d[k] = std::min(d[k], g.voxel * crossing(k, ok, p, o));
    });
  });
  // The level set's distance carried out across the band (a node is at most one spacing further
  // than its neighbour on its side), so that the field stays a distance: neighbours differ by
  // at most a spacing, which the contact list's slope bound relies on (sdf_slopes).
  for (int pass = 0; pass < int(std::ceil(kSdfBandVoxels)); ++pass) {
    std::vector<double> next(d);
    for_each_node(g, [&](const glm::ivec3& p, size_t k) {
      neighbours(p, [&](const glm::ivec3&, size_t ok) {
        if (inside[ok] == inside[k]) next[k] = std::min(next[k], d[ok] + g.voxel);
      });
    });
    d.swap(next);
  }
  for (size_t k = 0; k < g.nodes(); ++k) g.values[k] = float(inside[k] ? -d[k] : d[k]);
}

double triangle_winding(const dvec3& a, const dvec3& b, const dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double num = glm::dot(a, glm::cross(b, c));
  const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
  return std::atan2(num, den) / (2 * std::numbers::pi);
}

FastWindingNumber::FastWindingNumber(const SurfaceMesh& mesh, double accuracy) {
  const size_t n = mesh.triangles.size();
  order_.resize(n);
  for (uint32_t k = 0; k < n; ++k) order_[k] = k;
  // Corners in file order first; build() sorts order_ and then they are laid out in it.
  for (const glm::uvec3& t : mesh.triangles) {
    a_.push_back(mesh.positions[t[0]]);
    b_.push_back(mesh.positions[t[1]]);
    c_.push_back(mesh.positions[t[2]]);
  }
  if (n > 0) build(0, uint32_t(n), accuracy);
  std::vector<dvec3> a(n), b(n), c(n);
  for (size_t k = 0; k < n; ++k) a[k] = a_[order_[k]], b[k] = b_[order_[k]], c[k] = c_[order_[k]];
  a_.swap(a), b_.swap(b), c_.swap(c);
}

// Splits at the median of the longest axis of the triangles' centroids; leaves of at most 8.
int32_t FastWindingNumber::build(uint32_t first, uint32_t count, double beta) {
  const int32_t id = int32_t(nodes_.size());
  nodes_.emplace_back();
  Node node;
  double area = 0;
  dvec3 lo(INFINITY), hi(-INFINITY);
  for (uint32_t k = first; k < first + count; ++k) {
    const uint32_t t = order_[k];
    const dvec3 v = glm::cross(b_[t] - a_[t], c_[t] - a_[t]) * 0.5;
    const double w = glm::length(v);
    const dvec3 centroid = (a_[t] + b_[t] + c_[t]) / 3.0;
    node.area_vector += v;
    node.centre += centroid * w;
    area += w;
    lo = glm::min(lo, centroid);
    hi = glm::max(hi, centroid);
  }
  if (area > 0) node.centre /= area;
  else node.centre = (lo + hi) * 0.5;
  double r2 = 0;
  for (uint32_t k = first; k < first + count; ++k) {
    const uint32_t t = order_[k];
    for (const dvec3& v : {a_[t], b_[t], c_[t]}) r2 = std::max(r2, glm::dot(v - node.centre, v - node.centre));
  }
  node.radius2 = beta * beta * r2;
  node.first = first;
  node.count = count;
  if (count > 8) {
    const dvec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const uint32_t half = count / 2;
    auto key = [&](uint32_t t) { return a_[t][axis] + b_[t][axis] + c_[t][axis]; };
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](uint32_t s, uint32_t t) { return key(s) < key(t); });
    node.left = build(first, half, beta);
    node.right = build(first + half, count - half, beta);
  }
  nodes_[size_t(id)] = node;
  return id;
}

double FastWindingNumber::operator()(const dvec3& p) const {
  if (nodes_.empty()) return 0;
  double sum = 0;
  int32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[size_t(stack[--top])];
    const dvec3 r = node.centre - p;
    const double d2 = glm::dot(r, r);
    if (d2 > node.radius2) {
      // Far: the cluster as one dipole, its solid angle area_vector . r / |r|^3 over 4 pi.
      sum += glm::dot(node.area_vector, r) / (4 * std::numbers::pi * d2 * std::sqrt(d2));
    } else if (node.left < 0) {
      for (uint32_t k = node.first; k < node.first + node.count; ++k)
        sum += triangle_winding(a_[k] - p, b_[k] - p, c_[k] - p);
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return sum;
}

}  // namespace clothsim

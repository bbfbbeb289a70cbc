// Fabric in physical units (issue 44; docs/materials.md): the membrane's and the hinges'
// formulas against their energies, and the closed forms of a cloth made of them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "material_fixtures.hpp"
#include "../compute/shared/membrane.glsl"

using namespace clothsim;

namespace {

using V3 = glm::dvec3;
using V4 = glm::dvec4;

// St Venant-Kirchhoff in the material frame, written out on its own (not membrane.glsl's): c =
// (warp, weft, compression ratio, shear); a shortened direction takes the ratio of its stiffness.
double membrane_energy(V3 xi, V3 xa, V3 xb, V4 dminv, double area, V4 c) {
  const V3 f0 = (xa - xi) * dminv.x + (xb - xi) * dminv.z, f1 = (xa - xi) * dminv.y + (xb - xi) * dminv.w;
  const double e00 = 0.5 * (glm::dot(f0, f0) - 1), e11 = 0.5 * (glm::dot(f1, f1) - 1), e01 = 0.5 * glm::dot(f0, f1);
  const double c11 = e00 < 0 ? c.x * c.z : c.x, c22 = e11 < 0 ? c.y * c.z : c.y;
  return area * (0.5 * c11 * e00 * e00 + 0.5 * c22 * e11 * e11 + 2 * c.w * e01 * e01);
}

double hinge_energy(V3 xs, V3 x0, V3 x1, V3 x2, V4 k, double rest) {
  const V3 v = xs * k.x + x0 * k.y + x1 * k.z + x2 * k.w;
  return 0.5 * (glm::length(v) - rest) * (glm::length(v) - rest);
}

template <class E> V3 numeric_force(E energy, V3 x) {
  V3 f(0.0);
  for (int c = 0; c < 3; ++c) {
    const double h = 1e-7;
    V3 p = x, m = x;
    p[c] += h;
    m[c] -= h;
    f[c] = -(energy(p) - energy(m)) / (2 * h);
  }
  return f;
}

}  // namespace

TEST_CASE("A membrane triangle's force is minus its energy's gradient, its block positive semi-definite", "[materials]") {
  const V3 xa(0.011, 0.002, -0.001), xb(-0.002, 0.001, 0.012);
  // Rest: corners at (0, 0), (0.01, 0), (0, 0.01) in the material frame.
  const V4 dminv(100, 0, 0, 100);
  const V4 c(2000, 1000, 0.2, 30);
  // Stretched both ways (the first two and the last), and with the warp shortened (the third).
  for (V3 xi : {V3(0.0), V3(0.001, -0.002, 0.0005), V3(0.004, 0.001, 0.003), V3(-0.0005, 0.0, -0.0005)}) {
    shared::Sym3<double> h = shared::sym3_diagonal(0.0);
    const V3 f = shared::add_membrane_terms(V3(0.0), h, xi, xa, xb, dminv, 5e-5, c, true);
    const V3 expect = numeric_force([&](V3 x) { return membrane_energy(x, xa, xb, dminv, 5e-5, c); }, xi);
    CHECK(glm::length(f - expect) <= 1e-5 * glm::length(expect) + 1e-9);
    // Positive semi-definite: the block's leading minors.
    CHECK(h.a.x >= 0);
    CHECK(h.a.x * h.b.x - h.a.y * h.a.y >= -1e-12);
  }
}

TEST_CASE("A hinge's force is minus its energy's gradient, flat or with a rest curvature", "[materials]") {
  const V3 x0(0.01, 0.001, 0), x1(0.0, 0.0, 0.01), x2(0.012, -0.002, 0.011);
  const V4 k(1.3, -0.7, 0.4, -1.0);
  for (double rest : {0.0, 0.003}) {
    shared::Sym3<double> h = shared::sym3_diagonal(0.0);
    const V3 xs(0.002, 0.004, 0.001);
    const V3 f = shared::add_hinge_terms(V3(0.0), h, xs, x0, x1, x2, k, rest);
    const V3 expect = numeric_force([&](V3 x) { return hinge_energy(x, x0, x1, x2, k, rest); }, xs);
    CHECK(glm::length(f - expect) <= 1e-5 * glm::length(expect) + 1e-9);
  }
}


using test::strip;
using test::pin_columns;
using test::run;
using test::column;


// Peirce's cantilever (ASTM D1388): a strip overhanging by l = 2 (B/w)^(1/3) droops until the
// chord from the clamp's edge to its tip makes 41.5° with the horizontal (the exact elastica
// for w l^3 / B = 8 gives 41.49°). A 2.5 cm strip clamped by pinning its first 2 cm.
TEST_CASE("A strip of bending rigidity B droops to Peirce's 41.5° chord at three resolutions", "[materials][slow]") {
  const double w = 0.2 * 9.81;
  for (double b : {1e-5, 1e-4}) {
    const double l = 2 * std::cbrt(b / w);
    for (int along : {8, 12, 16}) {
      const double h = l / along;
      const int clamp = int(std::lround(0.02 / h)), nw = along + clamp + 1, nh = int(std::lround(0.025 / h)) + 1;
      const Scene scene = strip(nw, nh, h, pin_columns(0, clamp, nh), V3(0, -9.81, 0), "2000", 20, b);
      const State<double> s = run<double>(scene, 180);
      const V3 root = column(s, nw, nh, clamp), tip = column(s, nw, nh, nw - 1);
      const double angle = std::atan2(root.y - tip.y, tip.x - root.x) * 180 / M_PI;
      INFO("B " << b << " N·m, " << along << " spacings along the overhang: chord " << angle << "°");
      CHECK(std::abs(angle - 41.5) < 2.0);
    }
  }
}

// A strip hanging under its own weight w = density g from its top edge stretches by
// w L^2 / (2 stretch): the tension at each height is the weight below it. Warp along x, weft
// along y: the strip hangs along each in turn (gravity along -x, then -z).
TEST_CASE("A hanging strip stretches by its weight over `stretch`, warp and weft apart", "[materials]") {
  const double h = 0.02, warp = 1500, weft = 600, w = 0.2 * 9.81;
  const int n = 26, across = 5;  // 0.5 m along, 8 cm across
  const double length = (n - 1) * h;
  for (int along_x = 1; along_x >= 0; --along_x) {
    const int nw = along_x ? n : across, nh = along_x ? across : n;
    std::string pins;
    for (int k = 0; k < (along_x ? nh : nw); ++k)
      pins += fmt::format("{}[{},{}]", k ? "," : "", along_x ? nw - 1 : k, along_x ? k : nh - 1);
    const Scene scene =
        strip(nw, nh, h, pins, along_x ? V3(-9.81, 0, 0) : V3(0, 0, -9.81), fmt::format("[{}, {}]", warp, weft), 20, 1e-6);
    const State<double> s = run<double>(scene, 90);
    // The free end's mean displacement along the strip.
    double moved = 0;
    for (int k = 0; k < (along_x ? nh : nw); ++k) {
      const size_t i = along_x ? size_t(k * nw) : size_t(k);
      moved += along_x ? -(s.pos[i].x - 0.0) : -(s.pos[i].z - 0.0);
    }
    moved /= double(along_x ? nh : nw);
    const double expect = w * length * length / (2 * (along_x ? warp : weft));
    INFO((along_x ? "warp" : "weft") << ": stretched " << moved << " m, closed form " << expect << " m");
    CHECK(std::abs(moved / expect - 1) < 0.02);
  }
}

// A sheet pinned along its lower edge with gravity in its plane along x is a stack of layers in
// simple shear: at height y the layers above pull with w (H - y) per length, the shear angle is
// that over `shear`, and the top edge moves w H^2 / (2 shear) (far from the free ends, which
// the stretch stiffness, 100 times the shear, keeps short).
TEST_CASE("A sheet sheared by its weight in its plane returns `shear`", "[materials]") {
  const double h = 0.01, shear = 20, w = 0.2 * 9.81;
  const int nw = 61, nh = 11;  // 0.6 m by 0.1 m
  std::string pins;
  for (int x = 0; x < nw; ++x) pins += fmt::format("{}[{},0]", x ? "," : "", x);
  const Scene scene = strip(nw, nh, h, pins, V3(9.81, 0, 0), "2000", shear, 1e-6);
  const State<double> s = run<double>(scene, 90);
  const double height = (nh - 1) * h;
  const double moved = s.pos[size_t((nh - 1) * nw + nw / 2)].x - (nw / 2) * h;
  const double expect = w * height * height / (2 * shear);
  INFO("top edge moved " << moved << " m, closed form " << expect << " m");
  CHECK(std::abs(moved / expect - 1) < 0.05);
}

// max_stretch holds a material cloth too: its structural springs add no force (the membrane is
// its stretch) but stay in the limit's passes (simulation.stretch_passes). A membrane of 5 N/m
// hanging from its top corners would stretch by tens of percent; with two passes no structural
// spring ends a frame longer than (1 + max_stretch) rest, to the passes' convergence.
TEST_CASE("A material cloth's max_stretch passes hold its structural springs at the limit", "[materials]") {
  auto longest = [](int passes) {
    Scene scene = parse_scene(fmt::format(R"({{"cloth": {{"width": 0.4, "height": 0.4, "num_width_points": 9,
        "num_height_points": 9, "thickness": 0.005, "orientation": 1, "pinned": [[0, 8], [8, 8]],
        "material": {{"density": 0.2, "stretch": 5, "shear": 1, "bending": 1e-6}}}},
        "simulation": {{"solver": "fabric", "self_collision": false, "max_stretch": 0.05, "stretch_passes": {}}}}})",
                                          passes), "<limit>");
    const ClothModel m = build_cloth(scene);
    const State<double> s = run<double>(scene, 30);
    double worst = 0;
    for (const Spring& sp : m.springs)
      if (sp.type == SpringType::Structural)
        worst = std::max(worst, glm::length(V3(s.pos[sp.i]) - V3(s.pos[sp.j])) / sp.rest);
    return worst;
  };
  const double free = longest(0), held = longest(2);
  INFO("longest structural spring: " << free << " x rest without the passes, " << held << " x with two");
  CHECK(free > 1.2);
  CHECK(held < 1.05 * 1.01);
}

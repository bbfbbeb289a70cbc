// GPU hashed-grid self-collision (DESIGN.md §1 step 3) against the CPU reference: the
// multi-level prefix scan, the hash build, contacts across cells and across hash-table
// collisions, a folded cloth, determinism of whole runs, and the heap of the classic scene.
#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <random>

#include "gl_test_support.hpp"
#include "gpu_simulator.hpp"
#include "prefix_scan.hpp"
#include "reference.hpp"
#include "test_helpers.hpp"

using namespace clothsim;

namespace {

using Positions = std::vector<Vec4<float>>;
using Cell = std::array<int32_t, 3>;

std::filesystem::path compute_dir() { return test::source_path("compute"); }

using test::mismatches;

float max_diff(const Positions& a, const Positions& b) {
  float m = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) m = std::max(m, std::abs(a[i][k] - b[i][k]));
  return m;
}

// One pass from an identical state: bit for bit on llvmpipe (DESIGN.md §6), else within 1e-6 m.
void check_same_pass_result(const Positions& gpu, const Positions& cpu) {
  INFO("max |GPU - CPU| = " << max_diff(gpu, cpu) << " m");
  if (gl::gl_renderer_is_llvmpipe())
    CHECK(mismatches(gpu, cpu) == 0);
  else
    CHECK(max_diff(gpu, cpu) <= 1e-6f);
}

Cell cell_of(const Vec4<float>& p, const Constants<float>& c) {
  return {cell_coord(p.x, c.inv_cell), cell_coord(p.y, c.inv_cell), cell_coord(p.z, c.inv_cell)};
}
uint32_t bucket_of(const Cell& k, uint32_t table) { return hash_cell(k[0], k[1], k[2], table); }

// A scene whose particles a test places by hand; collide() runs self-collision on both sides.
struct Placed {
  Scene scene;
  ClothModel model = build_cloth(scene.cloth);
  Constants<float> c = make_constants<float>(scene, model);
  State<float> s = initial_state<float>(model);
  explicit Placed(Scene sc) : scene(std::move(sc)) {}
  // The GPU result; `s` is left after the CPU pass.
  Positions collide() {
    s.prev = s.pos;
    GpuSimulator gpu(scene, model, compute_dir());
    gpu.upload(s);
    gpu.collide_self();
    State<float> g;
    gpu.download(g);
    collide_self(c, s);
    return g.pos;
  }
  // The particles not placed by the test go far apart, out of everyone's reach.
  void park_from(int first) {
    for (int i = first; i < model.count(); ++i) s.pos[i] = Vec4<float>(5.f + 0.5f * float(i), 7.f, -3.f, s.pos[i].w);
  }
};

// Particle i moved from `before` to `after` by the average push of `others` (§1.3), in double.
void check_pushed(const Positions& after, const Positions& before, int i, std::vector<int> others,
                  const Constants<float>& c) {
  glm::dvec3 push(0);
  for (int j : others) {
    const glm::dvec3 e = glm::dvec3(before[i]) - glm::dvec3(before[j]);
    push += e * ((double(c.contact_distance) - glm::length(e)) / glm::length(e));
  }
  push /= double(others.size()) * double(c.steps);
  for (int k = 0; k < 3; ++k) CHECK(double(after[i][k]) - double(before[i][k]) == Approx(push[k]).margin(1e-7));
}

}  // namespace

TEST_CASE("the GPU prefix scan is exclusive at every length and leaves elements past it alone",
          "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  const size_t wg = WORKGROUP_SIZE, block = PrefixScan::kBlock;
  // One chunk up to SCAN_CHUNK = 32; two levels up to 32^2; 70001 and 2^17 + 5 need four.
  const std::vector<size_t> sizes = {1,         2,         wg - 1,     wg,    wg + 1,           block - 1, block,
                                     block + 1, 2 * block, 65536,      65537, 70001, 100003, (1u << 17) + 5};
  PrefixScan scan(compute_dir(), *std::max_element(sizes.begin(), sizes.end()));
  CHECK(scan.dispatches(block) == 1);
  CHECK(scan.dispatches(block * block) == 3);
  CHECK(scan.dispatches(70001) == 7);  // 70001 -> 2188 -> 69 -> 3 chunk totals: 4 scans, 3 add-backs
  std::mt19937 rng(17);
  for (size_t n : sizes) {
    INFO("count " << n << ", " << scan.dispatches(n) << " dispatches");
    std::vector<uint32_t> data(n + 41);  // 41 elements past the count that must survive
    for (auto& v : data) v = rng() % 16;
    gl::Buffer buffer("scan under test");
    gl::upload_vector(buffer, data);
    scan.scan(buffer, n);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<uint32_t> want = data;
    std::exclusive_scan(data.begin(), data.begin() + long(n), want.begin(), 0u);
    CHECK(mismatches(gl::download_vector<uint32_t>(buffer), want) == 0);
  }
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the GPU hash holds every particle once, in its own bucket, ascending, as the reference's",
          "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // 182^2 particles -> a 65536-bucket table (a four-level scan); about ten particles per cell.
  Placed t(test::make_scene(182, 182, 0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-2e-3f, 2e-3f);  // so cells hold irregular counts
  for (auto& p : t.s.pos) p = Vec4<float>(p.x + jitter(rng), p.y + jitter(rng), p.z + jitter(rng), p.w);
  GpuSimulator gpu(t.scene, t.model, compute_dir());
  gpu.upload(t.s);
  for (auto stage : {&GpuSimulator::count_cells, &GpuSimulator::scan_cells, &GpuSimulator::fill_cells,
                     &GpuSimulator::sort_cells})
    (gpu.*stage)();
  SpatialHash g;
  gpu.download_hash(g);
  SpatialHash& h = t.s.hash;
  std::vector<uint32_t> buckets, ids(t.s.pos.size());
  for (auto& p : t.s.pos) buckets.push_back(bucket_of(cell_of(p, t.c), h.table_size));
  std::iota(ids.begin(), ids.end(), 0u);
  count_cells(buckets, h);
  scan_cells(h);
  fill_cells(buckets, ids, h);
  sort_cells(h);
  REQUIRE(g.table_size == 65536);
  auto sorted = g.entries;
  std::sort(sorted.begin(), sorted.end());
  CHECK(mismatches(sorted, ids) == 0);  // every particle exactly once
  size_t wrong_bucket = 0, descending = 0, largest = 0;
  for (uint32_t b = 0; b < g.table_size; ++b) {
    largest = std::max<size_t>(largest, g.start[b + 1] - g.start[b]);
    for (uint32_t e = g.start[b]; e < g.start[b + 1]; ++e) {
      wrong_bucket += buckets[g.entries[e]] != b;
      descending += e > g.start[b] && g.entries[e - 1] >= g.entries[e];
    }
  }
  CHECK(largest > 4);  // buckets with many ids, so the sort has work to do
  CHECK(wrong_bucket == 0);
  CHECK(descending == 0);
  CHECK(mismatches(g.count, h.count) == 0);
  CHECK(mismatches(g.start, h.start) == 0);
  CHECK(mismatches(g.entries, h.entries) == 0);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("particles in contact across a cell boundary are found", "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  Placed t(test::make_scene(2, 2, 0));
  const float boundary = 10.f / t.c.inv_cell, centre = 20.5f / t.c.inv_cell;
  t.s.pos[0] = Vec4<float>(boundary - 0.003f, centre, centre, t.s.pos[0].w);
  t.s.pos[1] = Vec4<float>(boundary + 0.003f, centre, centre, t.s.pos[1].w);
  t.park_from(2);
  REQUIRE(cell_of(t.s.pos[0], t.c)[0] + 1 == cell_of(t.s.pos[1], t.c)[0]);
  const Positions before = t.s.pos;
  const Positions gpu = t.collide();
  check_same_pass_result(gpu, t.s.pos);
  check_pushed(gpu, before, 0, {1}, t.c);
  check_pushed(gpu, before, 1, {0}, t.c);
  CHECK(mismatches(Positions(gpu.begin() + 2, gpu.end()), Positions(before.begin() + 2, before.end())) == 0);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a neighbour whose bucket is visited twice is counted once", "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  Placed t(test::make_scene(8, 8, 0));  // 64 particles, 64 buckets
  const uint32_t table = t.s.hash.table_size;
  // A cell A whose +x neighbour's bucket is also the bucket of another of the 27 cells around
  // A (so that bucket is visited twice), while A's own bucket appears once among them.
  std::optional<Cell> a;
  // (Buckets run along x within a row, so it is the rows (y, z) that must collide.)
  for (int32_t z = 0; z < 200 && !a; ++z)
    for (int32_t y = 0; y < 200 && !a; ++y) {
      std::vector<uint32_t> around;
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) around.push_back(bucket_of({2 + dx, y + dy, z + dz}, table));
      auto times = [&](const Cell& k) { return std::count(around.begin(), around.end(), bucket_of(k, table)); };
      if (times({3, y, z}) >= 2 && times({2, y, z}) == 1) a = Cell{2, y, z};
    }
  REQUIRE(a.has_value());
  const float h = 1.f / t.c.inv_cell;
  const float bx = float((*a)[0] + 1) * h, cy = (float((*a)[1]) + 0.5f) * h, cz = (float((*a)[2]) + 0.5f) * h;
  // i near A's +x face, j across it (the doubly visited bucket), k beside i in A.
  t.s.pos[0] = Vec4<float>(bx - 0.003f, cy, cz, t.s.pos[0].w);
  t.s.pos[1] = Vec4<float>(bx + 0.003f, cy, cz, t.s.pos[1].w);
  t.s.pos[2] = Vec4<float>(bx - 0.003f, cy + 0.008f, cz, t.s.pos[2].w);
  t.park_from(3);
  INFO("cell A = (" << (*a)[0] << ", " << (*a)[1] << ", " << (*a)[2] << ")");
  REQUIRE(cell_of(t.s.pos[0], t.c) == *a);
  REQUIRE(cell_of(t.s.pos[2], t.c) == *a);
  REQUIRE(cell_of(t.s.pos[1], t.c) == Cell{(*a)[0] + 1, (*a)[1], (*a)[2]});
  const Positions before = t.s.pos;
  const Positions gpu = t.collide();
  check_same_pass_result(gpu, t.s.pos);
  // Counting j twice would give (2 push_j + push_k) / 3 instead of (push_j + push_k) / 2.
  check_pushed(gpu, before, 0, {1, 2}, t.c);
  check_pushed(gpu, before, 1, {0, 2}, t.c);
  check_pushed(gpu, before, 2, {0, 1}, t.c);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("a row of cells whose buckets wrap around the end of the table is searched whole",
          "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // collide_self reads the three cells of a row as one run of buckets; where the run passes
  // the table's end it must continue at bucket 0. Cell A = (2, y, z) with its -x neighbour
  // in the last bucket, A in bucket 0 and its +x neighbour in bucket 1.
  Placed t(test::make_scene(8, 8, 0));
  const uint32_t table = t.s.hash.table_size;
  std::optional<Cell> a;
  for (int32_t z = 0; z < 200 && !a; ++z)
    for (int32_t y = 0; y < 200 && !a; ++y)
      if (bucket_of({1, y, z}, table) == table - 1) a = Cell{2, y, z};
  REQUIRE(a.has_value());
  REQUIRE(bucket_of(*a, table) == 0);
  const float h = 1.f / t.c.inv_cell;  // the cell edge, equal to the contact distance
  const float lo = float((*a)[0]) * h, cy = (float((*a)[1]) + 0.5f) * h, cz = (float((*a)[2]) + 0.5f) * h;
  t.s.pos[0] = Vec4<float>(lo + 0.1f * h, cy, cz, t.s.pos[0].w);   // i in A
  t.s.pos[1] = Vec4<float>(lo - 0.1f * h, cy, cz, t.s.pos[1].w);   // j in the last bucket
  t.s.pos[2] = Vec4<float>(lo + 1.05f * h, cy, cz, t.s.pos[2].w);  // k in bucket 1
  t.park_from(3);
  INFO("cell A = (" << (*a)[0] << ", " << (*a)[1] << ", " << (*a)[2] << ")");
  REQUIRE(cell_of(t.s.pos[1], t.c) == Cell{(*a)[0] - 1, (*a)[1], (*a)[2]});
  REQUIRE(cell_of(t.s.pos[2], t.c) == Cell{(*a)[0] + 1, (*a)[1], (*a)[2]});
  const Positions before = t.s.pos;
  const Positions gpu = t.collide();
  check_same_pass_result(gpu, t.s.pos);
  check_pushed(gpu, before, 0, {1, 2}, t.c);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the GPU correction equals the reference's on a cloth folded onto itself", "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // 33x17 over 0.4 m: rows 9..16 folded back over rows 7..0, 0.6 thickness above them.
  Placed t(test::make_scene(33, 17, 0, {"cloth.width=0.4", "cloth.height=0.4"}));
  const float gap = 0.6f * float(t.scene.cloth.thickness), sx = 0.4f / 32, sz = 0.4f / 16;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> jitter(-1e-3f, 1e-3f);
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 33; ++x) {
      const int row = y <= 8 ? y : 16 - y;
      Vec4<float>& p = t.s.pos[t.model.index(x, y)];
      p = Vec4<float>(float(x) * sx + jitter(rng), 1.f + (y <= 8 ? 0.f : gap) + jitter(rng),
                      float(row) * sz + jitter(rng), p.w);
    }
  const Positions before = t.s.pos;
  const Positions gpu = t.collide();
  check_same_pass_result(gpu, t.s.pos);
  const size_t in_contact = mismatches(before, t.s.pos);  // particles the pass moved
  int across = 0;  // contact pairs between the two layers (within a layer x neighbours touch too)
  for (int i = 0; i < 9 * 33; ++i)
    for (int j = 9 * 33; j < t.model.count(); ++j)
      across += length3(Vec3<float>(before[i]) - Vec3<float>(before[j])) < t.c.contact_distance;
  WARN("folded cloth: " << in_contact << " of " << t.model.count() << " particles in contact, " << across
                        << " pairs across the fold; max |GPU - CPU| = " << max_diff(gpu, t.s.pos) << " m");
  CHECK(in_contact > size_t(t.model.count()) * 3 / 4);
  CHECK(across > 8 * 33);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("two GPU runs with self-collision are bitwise identical, and equal the reference on llvmpipe",
          "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // The selfCollision scene on a 17x17 grid: thickness scaled with the spacing (0.0095 * 49/16).
  const Scene scene = test::make_scene(17, 17, 1, {"cloth.thickness=0.0291"},
                                       R"(, "plane": {"point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5})");
  const ClothModel model = build_cloth(scene.cloth);
  const int substeps = 300;
  auto run_gpu = [&] {
    GpuSimulator gpu(scene, model, compute_dir());
    for (int k = 0; k < substeps; ++k) gpu.step();
    State<float> s;
    gpu.download(s);
    return s;
  };
  const State<float> a = run_gpu(), b = run_gpu();
  CHECK(mismatches(a.pos, b.pos) + mismatches(a.prev, b.prev) == 0);
  // The reference, pass by pass, counting the substeps in which self-collision moved something.
  const Constants<float> c = make_constants<float>(scene, model);
  State<float> s = initial_state<float>(model);
  int contact_steps = 0;
  for (int k = 0; k < substeps; ++k) {
    accumulate_forces(model, c, s);
    integrate(c, s);
    const Positions before = s.pos;
    collide_self(c, s);
    contact_steps += mismatches(before, s.pos) > 0;
    collide_objects(c, s);
    solve_length_constraints(model, c, s);
  }
  INFO(contact_steps << " of " << substeps << " substeps had self-contacts; max |GPU - CPU| = "
                     << max_diff(a.pos, s.pos) << " m");
  CHECK(contact_steps > substeps / 4);
  if (gl::gl_renderer_is_llvmpipe()) CHECK(mismatches(a.pos, s.pos) + mismatches(a.prev, s.prev) == 0);
  CHECK_NO_GL_ERRORS();
}

TEST_CASE("the selfCollision cloth heaps on the plane without non-neighbours closer than the thickness",
          "[gpu][self_collision]") {
  REQUIRE_GL_CONTEXT();
  // The classic scene as shipped: 50x50, 200 frames (6000 substeps; about 25 s on llvmpipe).
  const Scene scene = load_scene(test::source_path("scenes/selfCollision.json"));
  const ClothModel model = build_cloth(scene.cloth);
  GpuSimulator gpu(scene, model, compute_dir());
  for (int f = 0; f < 200; ++f) gpu.step_frame();
  State<float> s;
  gpu.download(s);
  // Pairs further than 2 grid steps apart in x or y share no spring (structural, shear, bending).
  const float thickness = float(scene.cloth.thickness);
  float closest = INFINITY, top = -INFINITY;
  int too_close = 0;
  for (int i = 0; i < model.count(); ++i) {
    top = std::max(top, s.pos[i].y);
    for (int j = i + 1; j < model.count(); ++j) {
      if (std::abs(i % model.nw - j % model.nw) <= 2 && std::abs(i / model.nw - j / model.nw) <= 2) continue;
      const float d = length3(Vec3<float>(s.pos[i]) - Vec3<float>(s.pos[j]));
      closest = std::min(closest, d);
      too_close += d < thickness;
    }
  }
  WARN("selfCollision after 200 frames: closest non-neighbours " << closest << " m (thickness " << thickness
                                                                 << " m), heap top at y = " << top << " m");
  CHECK(std::isfinite(closest));
  CHECK(top < 0.25f);  // it has fallen into a heap
  CHECK(too_close == 0);
  CHECK_NO_GL_ERRORS();
}

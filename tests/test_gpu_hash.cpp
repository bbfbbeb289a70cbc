// The GPU hashed grid against the reference: prefix scan, buckets, neighbours across cells and buckets.
#include "gpu_self_collision_fixtures.hpp"

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
  for (PassId stage : {PassId::count_cells, PassId::scan_cells, PassId::fill_cells, PassId::sort_cells})
    gpu.run(stage);
  SpatialHash g;
  gpu.state().download_hash(g);
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

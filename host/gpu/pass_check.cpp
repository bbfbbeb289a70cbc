#include "pass_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>

#include <fmt/format.h>

namespace clothsim {
namespace {

template <class T> size_t differing(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
  return n;
}

// What most passes write: every position, then every displacement (and with the multigrid
// solve every offset, which predict writes and fabric's predict reads).
std::vector<Vec4<float>> positions_and_displacements(const State<float>& st) {
  auto v = st.pos;
  v.insert(v.end(), st.disp.begin(), st.disp.end());
  if (st.offset.size() == st.pos.size()) v.insert(v.end(), st.offset.begin(), st.offset.end());
  return v;
}

PassError integer_result(const char* pass, size_t differ) {
  return {pass, differ ? INFINITY : 0.0, differ == 0, true, differ};
}

// Entries with each bucket sorted: fill_cells leaves the order within a bucket to the GPU's atomics.
std::vector<uint32_t> entries_as_sets(const SpatialHash& h, std::vector<uint32_t> entries) {
  for (uint32_t b = 0; b < h.table_size; ++b)
    std::sort(entries.begin() + h.start[b], entries.begin() + h.start[b + 1]);
  return entries;
}

// The four stages that build the hash and the response over it, each on the GPU from the
// CPU's hash before it. Leaves `s` after resolve_self_contacts.
void check_self_collision_stages(const Constants<float>& c, State<float>& s, GpuSimulator& gpu,
                                 std::vector<PassError>& out) {
  const size_t n = s.pos.size();
  std::vector<uint32_t> buckets(n), order(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::ivec3 cell = cell_of(s.pos[i], c.inv_cell);
    buckets[i] = hash_cell(cell.x, cell.y, cell.z, s.hash.table_size);
    order[n - 1 - i] = uint32_t(i);  // descending: a fill order sort_cells must undo
  }
  SpatialHash& h = s.hash;
  SpatialHash g;
  gpu.upload(s);
  count_cells(buckets, h);
  gpu.run(PassId::count_cells);
  gpu.state().download_hash(g);
  out.push_back(integer_result("count_cells", differing(g.count, h.count)));
  gpu.state().upload_hash(h);
  scan_cells(h);
  gpu.run(PassId::scan_cells);
  gpu.state().download_hash(g);
  out.push_back(integer_result("scan_cells", differing(g.start, h.start)));
  gpu.state().upload_hash(h);
  fill_cells(buckets, order, h);
  gpu.run(PassId::fill_cells);
  gpu.state().download_hash(g);
  out.push_back(integer_result("fill_cells (as a set per bucket)",
                               differing(g.count, h.count) +
                                   differing(entries_as_sets(h, g.entries), entries_as_sets(h, h.entries))));
  gpu.state().upload_hash(h);
  sort_cells(h);
  gpu.run(PassId::sort_cells);
  gpu.state().download_hash(g);
  std::vector<glm::vec4> want_sorted(n);
  for (size_t e = 0; e < n; ++e) want_sorted[e] = s.pos[h.entries[e]];
  out.push_back(integer_result("sort_cells (+ positions in cell order)",
                               differing(g.entries, h.entries) + differing(gpu.state().download_sorted_positions(), want_sorted)));
  // The GPU's hash and sorted positions are now the CPU's: the response reads them.
  resolve_self_contacts(c, s);
  gpu.run(PassId::resolve_self_contacts);
  State<float> r;
  gpu.download(r);
  const auto both = positions_and_displacements;
  const Deviation d = deviation(both(r), both(s));
  out.push_back({"resolve_self_contacts", d.max, d.bitwise});
}

// The multigrid solve's passes (a fabric scene only: the others have no hierarchy), each
// from the CPU's state and scratch before it, in solve_multigrid's order; judged on positions,
// displacements and the scratch, forces as the displacement they cause over a substep.
void check_multigrid_passes(const ClothModel& model, const Constants<float>& c, State<float>& s, GpuSimulator& gpu,
                            std::vector<PassError>& out) {
  const Hierarchy& h = *c.hierarchy;
  auto as_displacement = [&](Vec4<float> f) { return f.w > 0.f ? Vec4<float>(Vec3<float>(f) * (c.dt2 / f.w), 0.f) : Vec4<float>(0); };
  auto stream = [&](const State<float>& st) {
    auto v = st.pos;
    v.insert(v.end(), st.disp.begin(), st.disp.end());
    v.insert(v.end(), st.offset.begin(), st.offset.end());
    v.insert(v.end(), st.coarse_corr.begin(), st.coarse_corr.end());
    for (const auto& r : st.residual) v.push_back(as_displacement(r));
    for (const auto& r : st.coarse_rhs) v.push_back(as_displacement(r));
    return v;
  };
  State<float> g;
  auto check = [&](const std::string& name, const std::function<void()>& on_cpu, const std::function<void()>& on_gpu) {
    gpu.upload(s);
    gpu.passes().upload_multigrid(s);
    on_cpu();
    on_gpu();
    gpu.download(g);
    gpu.passes().download_multigrid(g);
    const Deviation d = deviation(stream(g), stream(s));
    out.push_back({name, d.max, d.bitwise});
  };
  check("compute_residuals", [&] { compute_residuals(model, c, s); }, [&] { gpu.run(PassId::compute_residuals); });
  const int levels = int(h.levels.size());
  auto sweep = [&](int l, int sweeps) {
    const int colours = int(h.levels[size_t(l)].colour_start.size()) - 1;
    check(fmt::format("smooth_corrections (level {}, {} x {} colours)", l + 1, sweeps, colours),
          [&] { smooth_level(c, l, sweeps, s); }, [&] { gpu.run(PassId::smooth_corrections, {.level = l, .sweeps = sweeps}); });
  };
  auto prolong = [&](int l) {
    check(fmt::format("prolong_corrections (level {})", l + 1), [&] { prolong_corrections(c, l, s); },
          [&] { gpu.run(PassId::prolong_corrections, {.level = l}); });
  };
  const int small = levels > 0 ? first_small_level(h) : 0;
  State<float> before_small;
  for (int l = 0; l < levels; ++l) {
    if (l == small) before_small = s;
    check(fmt::format("restrict_residuals (level {})", l + 1), [&] { restrict_residuals(c, l, s); },
          [&] { gpu.run(PassId::restrict_residuals, {.level = l}); });
  }
  if (levels > 0) {
    // The cycle restricts the small levels itself: from before their restrictions above, their
    // right-hand sides, residuals and corrections zeroed so that a step it skipped shows.
    s = before_small;
    for (uint32_t g = h.levels[size_t(small)].first; g < h.coarse_count(); ++g) {
      s.coarse_rhs[g] = s.coarse_corr[g] = s.residual[s.pos.size() + g] = Vec4<float>(0);
    }
    check(fmt::format("cycle_small_levels (levels {} to {}, {} coarsest sweeps)", small + 1, levels, kCoarsestSweeps),
          [&] { cycle_small_levels(c, s); }, [&] { gpu.run(PassId::cycle_small_levels); });
    // The small levels' prolongation and sweep as passes of their own too, from where the
    // cycle left them (each backend does the same to the same state), then back there.
    const State<float> cycled = s;
    for (int l = levels - 2; l >= small; --l) {
      prolong(l);
      sweep(l, kLevelSweeps);
    }
    s = cycled;
  }
  for (int l = small - 1; l >= 0; --l) {
    prolong(l);
    sweep(l, kLevelSweeps);
  }
  check("prolong_to_cloth", [&] { prolong_to_cloth(model, c, s); }, [&] { gpu.run(PassId::prolong_to_cloth); });
  check(fmt::format("relax_vertices ({} colours)", h.fine_colours()),
        [&] {
          for (int k = 0; k < h.fine_colours(); ++k) relax_vertices(model, c, k, s);
        },
        [&] { gpu.run(PassId::relax_vertices); });
}

// enforce_stretch_limit with settling passes, from the state with every free mass moved away
// from the cloth's centre by twice max_stretch (so that passes settle), then from `s` itself;
// and arm_stretch_pass by the number of settling passes each side ran. Leaves `s` as it was.
void check_settling_passes(const ClothModel& model, const Constants<float>& c, State<float>& s, GpuSimulator& gpu,
                           std::vector<PassError>& out) {
  const State<float> start = s;
  Vec3<float> centre(0.f);
  for (const auto& p : s.pos) centre = centre + Vec3<float>(p) * (1.f / float(s.pos.size()));
  const float scale = 1.f + 2.f * (c.stretch_limit - 1.f);
  for (auto& p : s.pos)
    if (p.w != 0.f) p = Vec4<float>(centre + (Vec3<float>(p) - centre) * scale, p.w);
  const State<float> stretched = s;
  for (const State<float>* from : {&stretched, &start}) {
    s = *from;
    const uint64_t cpu_before = s.stretch_settling_passes, gpu_before = gpu.state().stretch_settling_passes();
    gpu.upload(s);
    enforce_stretch_limit(model, c, s);
    gpu.passes().enforce_stretch_limit();
    State<float> g;
    gpu.download(g);
    const Deviation d = deviation(positions_and_displacements(g), positions_and_displacements(s));
    const char* from_what = from == &stretched ? ", stretched" : "";
    out.push_back({fmt::format("enforce_stretch_limit (settling{})", from_what), d.max, d.bitwise});
    const uint64_t cpu_ran = s.stretch_settling_passes - cpu_before, gpu_ran = gpu.state().stretch_settling_passes() - gpu_before;
    out.push_back(integer_result(fmt::format("arm_stretch_pass ({} settling passes{})", cpu_ran, from_what).c_str(),
                                 cpu_ran != gpu_ran));
  }
  s = start;
}

// The skinned colliders' two passes on the GPU for the substep the CPU has just skinned for
// (prepare_substep ran their twins on its palette): the vertices at both ends, then the boxes.
void check_skinning_passes(const Constants<float>& c, GpuSimulator& gpu, std::vector<PassError>& out) {
  // [from, to) of the skinned texels (the vertices at the end and the start, then the boxes).
  const auto part = [](std::vector<Vec4<float>> v, size_t from, size_t to) {
    return std::vector<Vec4<float>>(v.begin() + std::ptrdiff_t(std::min(from, v.size())), v.begin() + std::ptrdiff_t(std::min(to, v.size())));
  };
  const size_t n = c.skin_vertices, all = c.control.skinned.size();
  gpu.run(PassId::skin_colliders);
  const Deviation vertices = deviation(part(gpu.state().download_skinned(), 0, 2 * n), part(c.control.skinned, 0, 2 * n));
  gpu.run(PassId::fit_collider_boxes);
  const Deviation boxes = deviation(part(gpu.state().download_skinned(), 3 * n, all), part(c.control.skinned, 3 * n, all));
  out.push_back({"skin_colliders", vertices.max, vertices.bitwise});
  out.push_back({"fit_collider_boxes", boxes.max, boxes.bitwise});
}

// One pass on both sides from the CPU's current state; leaves the CPU after the pass.
struct PassCheck {
  const ClothModel& model;
  const Constants<float>& c;
  State<float>& s;
  GpuSimulator& gpu;
  std::vector<PassError>& out;
  std::array<bool, kPassCount> checked{};  // the rows checked alone so far
  using Stream = std::function<std::vector<Vec4<float>>(const State<float>&)>;
  void check(const std::string& name, const std::function<void()>& on_cpu, const std::function<void()>& on_gpu,
             const Stream& stream) {
    State<float> g;
    gpu.upload(s);
    on_cpu();
    on_gpu();
    gpu.download(g);
    const Deviation d = deviation(stream(g), stream(s));
    out.push_back({name, d.max, d.bitwise});
  }
  // A pass of the table alone (its row's name), its CPU twin and comparison the row's.
  void check(PassId pass) {
    const PassRow& r = row(pass);
    checked[size_t(pass)] = true;
    check(r.name, [&] { r.twin(model, c, s); }, [&] { gpu.run(pass); }, stream(r.compare));
  }
  // The same fused with collide_objects after it, as the step runs it.
  void check_fused(PassId pass) {
    const PassRow& r = row(pass);
    check(fmt::format("{} (+ collide_objects)", r.name), [&] { r.twin(model, c, s), collide_objects(c, s); },
          [&] { gpu.run(pass, {.collide_objects = true}); }, stream(r.compare));
  }
  // A force error matters by the displacement it causes in one substep: F * w * dt^2.
  Stream displacement_of(std::vector<Vec4<float>> State<float>::*forces) const {
    return [this, forces](const State<float>& st) {
      std::vector<Vec4<float>> v((st.*forces).size());
      for (size_t i = 0; i < v.size(); ++i) v[i] = (st.*forces)[i] * (s.pos[i].w * c.dt2);
      return v;
    };
  }
  Stream stream(Compare what) const {
    switch (what) {
      case Compare::wind: return displacement_of(&State<float>::wind);
      case Compare::forces: return displacement_of(&State<float>::force);
      case Compare::normals: return [](const State<float>& st) { return st.normal; };
      case Compare::positions:
      case Compare::none: break;
    }
    return positions_and_displacements;
  }
  // Every row with a twin not checked above that the scene runs (or only the checks do).
  void check_the_other_rows(uint16_t features) {
    for (const PassRow& r : kPasses)
      if (r.twin && !checked[size_t(r.id)] && runs(r, features | kCheckOnly | kPerFrame)) check(r.id);
  }
};

const PassCheck::Stream kBoth = positions_and_displacements;

// The unfused passes, then (from the same state) the fused ones GpuSimulator::step runs:
// collide_objects rides along with advance, or with collide_self when that is on.
void check_classic_passes(PassCheck& k) {
  const Constants<float>& c = k.c;
  State<float>& s = k.s;
  if (c.wind_enabled) k.check(PassId::compute_wind_forces);
  const State<float> start = s;
  k.check(PassId::accumulate_forces);
  k.check(PassId::integrate);
  s = start;
  const bool colliders = c.has_colliders();
  if (colliders && !c.self_collision) {
    k.check_fused(PassId::advance);
    k.checked[size_t(PassId::advance)] = true;  // the step never runs it alone here
  } else {
    k.check(PassId::advance);
  }
  if (c.self_collision) {
    const State<float> before = s;
    check_self_collision_stages(c, s, k.gpu, k.out);
    s = before;
    k.check("collide_self", [&] { collide_self(c, s); }, [&] { k.gpu.passes().collide_self(); }, kBoth);
    if (colliders) {
      s = before;
      k.check("collide_self (+ collide_objects)", [&] { collide_self(c, s), collide_objects(c, s); },
              [&] { k.gpu.passes().collide_self(true); }, kBoth);
    }
  }
  k.check(PassId::collide_objects);
  k.check(PassId::solve_length_constraints);
}

// The fabric solver's passes (a fabric scene only: predict writes the multigrid solve's
// offsets, which a classic scene has no buffer for): predict alone and with the colliders,
// the multigrid solve's passes from its state, then the settling passes from the solve's.
void check_fabric_passes(PassCheck& k) {
  const ClothModel& model = k.model;
  const Constants<float>& c = k.c;
  State<float>& s = k.s;
  const State<float> classic_done = s;
  k.check(PassId::predict);
  if (c.has_colliders()) {
    s = classic_done;
    k.check_fused(PassId::predict);
  }
  check_multigrid_passes(model, c, s, k.gpu, k.out);
  if (c.stretch_passes_max > c.stretch_passes) check_settling_passes(model, c, s, k.gpu, k.out);
}

}  // namespace

std::vector<PassError> check_passes(const Scene& scene, const ClothModel& model, GpuSimulator& gpu, int warmup) {
  CpuBackend<float> cpu(scene, model);
  for (int f = 0; f < warmup; ++f) cpu.step_frame();
  // Both sides at the same time: the moving colliders, pins and gusts of the next substep.
  cpu.prepare_substep();
  gpu.set_time(cpu.time());
  const Constants<float>& c = cpu.constants();
  State<float>& s = cpu.state();
  std::vector<PassError> out;
  PassCheck k{model, c, s, gpu, out};
  if (c.skin_vertices > 0) check_skinning_passes(c, gpu, out);
  check_classic_passes(k);
  if (c.multigrid) check_fabric_passes(k);
  k.check(PassId::compute_normals);
  k.check_the_other_rows(gpu.passes().features());
  return out;
}

}  // namespace clothsim

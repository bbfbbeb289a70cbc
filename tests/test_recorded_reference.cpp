// The CPU reference against values recorded from the build before the cloth became a mesh
// model (commit d3c791a, tests/golden/reference_hashes.txt): every shipped scene, in float and
// in double, must give bit for bit the positions and displacements it gave then (or since a
// change recorded in the file's comments: heap256, say, since it moved to fabric). A hash of the
// raw bits (FNV-1a over pos and disp, x y z w) catches any change, however small; the first
// particle's position is printed beside it so that a failure says how far things moved.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "backend.hpp"
#include "cloth/cloth.hpp"
#include "scene/scene.hpp"

namespace fs = std::filesystem;
using namespace clothsim;

namespace {

uint64_t fnv1a(uint64_t h, const void* data, size_t n) {
  auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

// The five classic scenes long enough to land on their plane and sphere; few frames for the
// rest (the hash sees any change, and CI runs this under sanitizers too).
int frames_for(const fs::path& file, const Scene& scene) {
  for (const char* classic : {"pinned2", "pinned4", "plane", "sphere", "selfCollision"})
    if (file.stem() == classic) return 100;
  return scene.particle_count() > 20000 ? 1 : 20;
}

template <class R> uint64_t run_hash(const Scene& scene, int frames) {
  const ClothModel model = build_cloth(scene);
  CpuBackend<R> cpu(scene, model);
  for (int f = 0; f < frames; ++f) cpu.step_frame();
  uint64_t h = 0xcbf29ce484222325ull;
  for (auto& p : cpu.state().pos) h = fnv1a(h, &p, sizeof(p));
  for (auto& d : cpu.state().disp) h = fnv1a(h, &d, sizeof(d));
  return h;
}

std::string line_for(const fs::path& file) {
  const Scene scene = load_scene(file);
  const int frames = frames_for(file, scene);
  return fmt::format("{} {} {:016x} {:016x}", file.filename().string(), frames, run_hash<float>(scene, frames),
                     run_hash<double>(scene, frames));
}

}  // namespace

TEST_CASE("every shipped scene gives the recorded CPU reference positions, bit for bit", "[recorded][slow]") {
  const fs::path root = CLOTHSIM_SOURCE_DIR;
  std::map<std::string, std::string> recorded;
  std::ifstream in(root / "tests/golden/reference_hashes.txt");
  REQUIRE(in);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') recorded[line.substr(0, line.find(' '))] = line;
  REQUIRE(recorded.size() >= 14);
  for (auto& [name, want] : recorded) {
    INFO(name);
    CHECK(line_for(root / "scenes" / name) == want);
  }
}

// Prints the lines of tests/golden/reference_hashes.txt (run by hand to record: `[.record]`).
TEST_CASE("record the CPU reference hashes", "[.record]") {
  const fs::path root = CLOTHSIM_SOURCE_DIR;
  std::vector<fs::path> files;
  for (auto& e : fs::directory_iterator(root / "scenes"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (auto& f : files) fmt::print("{}\n", line_for(f));
}

// texgen: the procedural textures are deterministic, tile seamlessly, the height maps use the
// whole 8-bit range, and the sky cube map follows the GL face table with no seams between faces.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>

#include <glm/geometric.hpp>
#include <stb/stb_image.h>

#include "texgen.hpp"

using namespace clothsim::texgen;

namespace {

// Sum over channels of |a - b| between two pixels of one image.
int pixel_diff(const Image& im, int x0, int y0, int x1, int y1) {
  int d = 0;
  for (int c = 0; c < im.channels; ++c) d += std::abs(int(im.at(x0, y0, c)) - int(im.at(x1, y1, c)));
  return d;
}

// Mean difference between column x0 and column x1 (or rows, when `rows`).
double mean_line_diff(const Image& im, int a, int b, bool rows) {
  double sum = 0;
  for (int k = 0; k < im.width; ++k) sum += rows ? pixel_diff(im, k, a, k, b) : pixel_diff(im, a, k, b, k);
  return sum / im.width;
}

struct Named {
  std::string name;
  std::function<Image(int)> make;
  int repeats;  // the pattern repeats this often across the tile (every pixel, for noise)
};

const Named kTileable[] = {{"fabric", make_fabric, kWeaveThreads},
                           {"checker", make_checker, 8},
                           {"height_weave", make_height_weave, kWeaveThreads},
                           {"height_bumps", make_height_bumps, 1 << 30}};

// A committed texture, decoded; empty (width 0) when it cannot be read.
Image read_committed(const std::string& file) {
  const std::string path = std::string(CLOTHSIM_SOURCE_DIR) + "/textures/" + file;
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 0);
  Image im;
  if (!data) return im;
  im = Image(w, h, channels);
  std::copy(data, data + im.pixels.size(), im.pixels.begin());
  stbi_image_free(data);
  return im;
}

void check_same_image(const Image& made, const Image& committed) {
  REQUIRE(committed.width > 0);
  CHECK(committed.width == made.width);
  CHECK(committed.height == made.height);
  CHECK(committed.channels == made.channels);
  if (committed.pixels.size() != made.pixels.size()) return;
  size_t differ = 0;
  for (size_t i = 0; i < made.pixels.size(); ++i) differ += made.pixels[i] != committed.pixels[i];
  INFO(differ << " of " << made.pixels.size() << " bytes differ");
  CHECK(differ == 0);
}

}  // namespace

// No random state, no input files: a run today writes the pixels the committed textures/ hold
// (made by an earlier run, at texgen's default sizes: 512, and 256 for the cube faces).
TEST_CASE("texgen writes the same pixels on every run: those of the committed textures/", "[texgen]") {
  for (const Named& t : kTileable) {
    INFO(t.name);
    const Image a = t.make(37);
    CHECK((a.width == 37 && a.height == 37 && a.pixels.size() == size_t(37 * 37 * a.channels)));
    check_same_image(t.make(512), read_committed(t.name + ".png"));
  }
  for (CubeFace f : kCubeFaces) {
    INFO(face_name(f));
    check_same_image(make_sky_face(f, 256), read_committed("sky_" + face_name(f) + ".png"));
  }
}

TEST_CASE("tileable textures wrap with no seam at the tile edge", "[texgen]") {
  // The pixel pair across the wrap (last, first) must differ no more than the pairs at the
  // same phase of the pattern inside the tile do (every pair, for noise).
  const int n = 128;
  for (const Named& t : kTileable) {
    const Image im = t.make(n);
    const int step = std::max(1, n / t.repeats);
    for (bool rows : {false, true}) {
      INFO(t.name << (rows ? " rows" : " columns"));
      double typical = 0;
      int pairs = 0;
      for (int k = step; k < n; k += step, ++pairs) typical += mean_line_diff(im, k - 1, k, rows);
      typical /= pairs;
      const double wrap = mean_line_diff(im, n - 1, 0, rows);
      INFO("wrap " << wrap << ", typical " << typical << " over " << pairs << " pairs");
      CHECK(wrap <= 1.5 * typical + 2);
    }
  }
}

TEST_CASE("the weave repeats every two threads, across the tile edge too", "[texgen]") {
  // A plain weave alternates over and under, so its height field has a period of two threads;
  // shifting by that period (wrapping around the tile) must give the same image.
  const int n = 128, period = 2 * n / kWeaveThreads;
  const Image im = make_height_weave(n);
  int worst = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      worst = std::max({worst, pixel_diff(im, x, y, (x + period) % n, y), pixel_diff(im, x, y, x, (y + period) % n)});
  CHECK(worst <= 1);
}

TEST_CASE("height maps span most of the 8-bit range", "[texgen]") {
  for (const Named& t : {kTileable[2], kTileable[3]}) {
    INFO(t.name);
    const Image im = t.make(512);  // the size textures/ ships
    REQUIRE(im.channels == 1);
    int lo = 255, hi = 0;
    double sum = 0, sum2 = 0;
    for (uint8_t p : im.pixels) lo = std::min(lo, int(p)), hi = std::max(hi, int(p)), sum += p, sum2 += double(p) * p;
    const double mean = sum / double(im.pixels.size());
    const double stddev = std::sqrt(sum2 / double(im.pixels.size()) - mean * mean);
    CHECK(lo <= 10);
    CHECK(hi >= 245);
    CHECK(stddev >= 30);
  }
}

TEST_CASE("cube_direction follows the GL cube map face table", "[texgen]") {
  // OpenGL 4.6 table 8.19: the face's axis at its centre, and where +s and +t lead.
  struct Row {
    CubeFace face;
    glm::vec3 axis, plus_s, plus_t;
  };
  const Row table[] = {{CubeFace::PosX, {1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
                       {CubeFace::NegX, {-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
                       {CubeFace::PosY, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}},
                       {CubeFace::NegY, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
                       {CubeFace::PosZ, {0, 0, 1}, {1, 0, 0}, {0, -1, 0}},
                       {CubeFace::NegZ, {0, 0, -1}, {-1, 0, 0}, {0, -1, 0}}};
  for (const Row& r : table) {
    INFO(face_name(r.face));
    CHECK(glm::length(cube_direction(r.face, 0.5f, 0.5f) - r.axis) < 1e-6f);
    CHECK(glm::length(cube_direction(r.face, 1.0f, 0.5f) - (r.axis + r.plus_s)) < 1e-6f);
    CHECK(glm::length(cube_direction(r.face, 0.5f, 1.0f) - (r.axis + r.plus_t)) < 1e-6f);
    for (float s = 0.05f; s < 1; s += 0.1f)
      for (float t = 0.05f; t < 1; t += 0.1f) {
        const FaceCoord fc = cube_face_coord(cube_direction(r.face, s, t));
        CHECK(fc.face == r.face);
        CHECK(fc.s == Approx(s).margin(1e-6));
        CHECK(fc.t == Approx(t).margin(1e-6));
      }
  }
}

TEST_CASE("sky cube map faces meet with no seam", "[texgen]") {
  // For every edge texel of every face, step one texel outward: the GL face selection lands on
  // the adjacent face, whose texel there must look like a neighbour on the same face does.
  const int n = 33;
  Image faces[6];
  for (CubeFace f : kCubeFaces) faces[int(f)] = make_sky_face(f, n);
  for (CubeFace f : kCubeFaces) {
    for (int edge = 0; edge < 4; ++edge) {
      const int dx = edge == 0 ? -1 : edge == 1 ? 1 : 0, dy = edge == 2 ? -1 : edge == 3 ? 1 : 0;
      double across = 0, inward = 0;
      int worst = 0, worst_inward = 0;
      for (int k = 0; k < n; ++k) {
        const int x = dx < 0 ? 0 : dx > 0 ? n - 1 : k, y = dy < 0 ? 0 : dy > 0 ? n - 1 : k;
        const float s = (float(x + dx) + 0.5f) / float(n), t = (float(y + dy) + 0.5f) / float(n);
        const FaceCoord fc = cube_face_coord(cube_direction(f, s, t));
        INFO(face_name(f) << " edge " << edge << " texel " << k << " -> " << face_name(fc.face));
        REQUIRE(fc.face != f);
        REQUIRE(glm::dot(cube_direction(fc.face, 0.5f, 0.5f), cube_direction(f, 0.5f, 0.5f)) == 0.0f);
        const int nx = std::clamp(int(fc.s * float(n)), 0, n - 1), ny = std::clamp(int(fc.t * float(n)), 0, n - 1);
        int d = 0, d_in = pixel_diff(faces[int(f)], x, y, x - dx, y - dy);
        for (int c = 0; c < 3; ++c) d += std::abs(int(faces[int(f)].at(x, y, c)) - int(faces[int(fc.face)].at(nx, ny, c)));
        across += d, inward += d_in;
        worst = std::max(worst, d), worst_inward = std::max(worst_inward, d_in);
      }
      INFO(face_name(f) << " edge " << edge << ": mean across " << across / n << ", inward " << inward / n
                        << "; worst across " << worst << ", inward " << worst_inward);
      CHECK(across / n <= 1.5 * inward / n + 2);
      CHECK(worst <= 2 * worst_inward + 6);
    }
  }
}

TEST_CASE("the sky is blue above, the ground below is darker and the sun is brightest", "[texgen]") {
  const glm::vec3 up = sky_color({0, 1, 0}), down = sky_color({0, -1, 0}), horizon = sky_color({1, 0.001f, 0});
  const glm::vec3 sun = sky_color({0.6f, 1.4f, 0.9f});
  CHECK(up.b > up.r + 0.3f);
  CHECK(down.r + down.g + down.b < 0.5f * (horizon.r + horizon.g + horizon.b));
  CHECK(sun.r + sun.g + sun.b > 2.7f);
}

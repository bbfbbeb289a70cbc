// The 2D textures and PNG output. Each texture is a function of (u, v) in [0, 1)^2, averaged
// over 4x4 sub-samples per pixel so edges are antialiased; everything periodic uses integer
// lattices that wrap at the tile edge, so the textures tile seamlessly.
#include "texgen.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/common.hpp>
#include <stb/stb_image_write.h>

#include "texgen_detail.hpp"

namespace clothsim::texgen {

namespace detail {

// Integer hash (Chris Wellons' lowbias32): the only source of "randomness", so output is fixed.
uint32_t hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

uint32_t hash(int a, int b, uint32_t seed) { return hash(uint32_t(a) ^ hash(uint32_t(b) ^ hash(seed))); }

float unit(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

float value_noise(float x, float y, int period_x, int period_y, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  auto wrap = [](int i, int p) { return ((i % p) + p) % p; };
  const int x0 = wrap(int(fx), period_x), x1 = wrap(int(fx) + 1, period_x);
  const int y0 = wrap(int(fy), period_y), y1 = wrap(int(fy) + 1, period_y);
  // Quintic fade: continuous slope and curvature across lattice lines (smooth bump normals).
  auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const float sx = fade(tx), sy = fade(ty);
  const float a = unit(hash(x0, y0, seed)), b = unit(hash(x1, y0, seed));
  const float c = unit(hash(x0, y1, seed)), d = unit(hash(x1, y1, seed));
  return (a + (b - a) * sx) * (1 - sy) + (c + (d - c) * sx) * sy;
}

float fbm(float u, float v, int base_period, int octaves, uint32_t seed) {
  float sum = 0, amplitude = 0.5f, norm = 0;
  int period = base_period;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * value_noise(u * float(period), v * float(period), period, period, seed + uint32_t(o));
    norm += amplitude;
    amplitude *= 0.5f;
    period *= 2;
  }
  return sum / norm;
}

std::vector<glm::vec3> supersample(int size, const std::function<glm::vec3(float, float)>& f) {
  constexpr int n = 4;
  std::vector<glm::vec3> out(size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      glm::vec3 sum(0);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          sum += f((float(x) + (float(i) + 0.5f) / n) / float(size), (float(y) + (float(j) + 0.5f) / n) / float(size));
      out[size_t(y) * size + x] = sum / float(n * n);
    }
  return out;
}

Image quantize(int size, const std::vector<glm::vec3>& colors, int channels) {
  Image im(size, size, channels);
  for (size_t p = 0; p < colors.size(); ++p)
    for (int c = 0; c < channels; ++c)
      im.pixels[p * channels + c] = uint8_t(std::lround(std::clamp(colors[p][c], 0.0f, 1.0f) * 255.0f));
  return im;
}

WeaveSample weave_at(float u, float v) {
  constexpr float pi = std::numbers::pi_v<float>;
  constexpr float half_width = 0.42f;  // of a thread, in thread spacings: leaves small gaps
  const float U = u * kWeaveThreads, V = v * kWeaveThreads;
  const int i = int(std::floor(U)), j = int(std::floor(V));
  const float a = U - float(i) - 0.5f, b = V - float(j) - 0.5f;
  // Round yarn cross-section; negative where the point is off the thread.
  auto profile = [](float x) {
    const float r = x / half_width;
    return r * r < 1 ? std::sqrt(1 - r * r) : -1.0f;
  };
  const float pa = profile(a), pb = profile(b);
  // Plain weave: warp i is over weft j where i + j is even; each thread rises and dips as a
  // cosine of period two crossings (kWeaveThreads is even, so it wraps at the tile edge).
  const float warp = pa < 0 ? -1 : 0.5f + 0.25f * std::cos(pi * (V - 0.5f - float(i))) + 0.25f * pa;
  const float weft = pb < 0 ? -1 : 0.5f - 0.25f * std::cos(pi * (U - 0.5f - float(j))) + 0.25f * pb;
  if (warp < 0 && weft < 0) return {0, false, true, 0, 0, 0};
  if (warp >= weft) return {warp, true, false, a / half_width, V, i};
  return {weft, false, false, b / half_width, U, j};
}

}  // namespace detail

using namespace detail;

Image make_fabric(int size) {
  const glm::vec3 warp_color(0.16f, 0.30f, 0.52f), weft_color(0.36f, 0.50f, 0.68f);
  auto color = [&](float u, float v) {
    const WeaveSample s = weave_at(u, v);
    if (s.gap) return weft_color * 0.22f;
    const uint32_t seed = s.warp ? 11u : 23u;
    const float tint = 1 + 0.10f * (unit(hash(s.index, 0, seed)) - 0.5f);
    // Fibres run along the thread with a slight twist; the slant (F/4 fibres per crossing)
    // times kWeaveThreads is a whole number of fibre periods, so it still wraps.
    constexpr int fibres = 6;
    const float c = (s.across * 0.5f + 0.5f) * fibres + s.along * fibres / 4;
    const float fibre = value_noise(c, s.along * 3, fibres, 3 * kWeaveThreads, seed + uint32_t(s.index) * 7);
    const float fine = value_noise(2 * c, s.along * 6, 2 * fibres, 6 * kWeaveThreads, seed + 101);
    const float striation = 0.82f + 0.22f * fibre + 0.10f * fine;
    const float shading = 0.30f + 0.70f * s.height;  // low parts of a thread sit in shadow
    const float mottle = 1 + 0.10f * (fbm(u, v, 4, 3, 7) - 0.5f);
    return (s.warp ? warp_color : weft_color) * (tint * striation * shading * mottle);
  };
  return quantize(size, supersample(size, color), 3);
}

Image make_checker(int size) {
  constexpr int squares = 8;
  const glm::vec3 light(0.88f, 0.86f, 0.80f), dark(0.22f, 0.40f, 0.62f), line(0.08f, 0.08f, 0.10f);
  const float square_px = float(size) / squares;
  auto color = [&](float u, float v) {
    const float x = u * squares, y = v * squares;
    const int i = int(std::floor(x)), j = int(std::floor(y));
    // Distance in pixels to the nearest square edge; lines are two pixels wide, split across
    // the edge, so the one on the tile border wraps.
    const float fx = x - float(i), fy = y - float(j);
    const float edge_px = std::min(std::min(fx, 1 - fx), std::min(fy, 1 - fy)) * square_px;
    if (edge_px < 1.0f) return line;
    return (i + j) % 2 == 0 ? light : dark;
  };
  return quantize(size, supersample(size, color), 3);
}

Image make_height_weave(int size) {
  return quantize(size, supersample(size, [](float u, float v) { return glm::vec3(weave_at(u, v).height); }), 1);
}

Image make_height_bumps(int size) {
  auto samples = supersample(size, [](float u, float v) { return glm::vec3(fbm(u, v, 4, 4, 1234)); });
  // Stretch to the full range so bump and displacement strengths mean the same at any size.
  float lo = samples[0].x, hi = samples[0].x;
  for (auto& s : samples) lo = std::min(lo, s.x), hi = std::max(hi, s.x);
  for (auto& s : samples) s = glm::vec3((s.x - lo) / (hi - lo));
  return quantize(size, samples, 1);
}

void write_png(const Image& image, const std::filesystem::path& path) {
  stbi_write_png_compression_level = 9;  // smaller files; the images are fixed anyway
  if (!stbi_write_png(path.string().c_str(), image.width, image.height, image.channels, image.pixels.data(),
                      image.width * image.channels))
    throw std::runtime_error(path.string() + ": cannot write the PNG file");
}

}  // namespace clothsim::texgen

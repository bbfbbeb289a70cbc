// texgen: the project's procedural textures (fabric, checker, height maps, sky cube map).
// Everything is a pure function of the image size: no input files, no random state, so the
// same build writes byte-identical PNGs every run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace clothsim::texgen {

// 8-bit image, rows top first (the order PNG files and stb use), channels interleaved.
struct Image {
  int width = 0, height = 0, channels = 0;  // channels: 1 grey, 3 RGB
  std::vector<uint8_t> pixels;

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(size_t(w) * h * c) {}
  uint8_t at(int x, int y, int c = 0) const { return pixels[(size_t(y) * width + x) * channels + c]; }
  uint8_t& at(int x, int y, int c = 0) { return pixels[(size_t(y) * width + x) * channels + c]; }
};

// Threads per tile in each direction of the plain weave; fabric and height_weave share it.
inline constexpr int kWeaveThreads = 32;

// Plain-weave fabric colour (RGB), tileable in u and v.
Image make_fabric(int size);
// UV checker: 8x8 squares in two colours with thin grid lines (RGB), tileable.
Image make_checker(int size);
// Height of the same weave as make_fabric (grey, 255 = top of a thread crossing over), tileable.
Image make_height_weave(int size);
// Smooth rolling bumps: tileable fBm value noise, stretched to the full 0..255 range (grey).
Image make_height_bumps(int size);

// Cube map faces in GL order (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face).
enum class CubeFace { PosX, NegX, PosY, NegY, PosZ, NegZ };
inline constexpr CubeFace kCubeFaces[6] = {CubeFace::PosX, CubeFace::NegX, CubeFace::PosY,
                                           CubeFace::NegY, CubeFace::PosZ, CubeFace::NegZ};
// "posx", "negx", ... as used in the file names sky_posx.png, ...
std::string face_name(CubeFace face);

// Direction (not normalised) that the GL cube map face table maps to face coordinates (s, t) in
// [0, 1]. Texel (x, y) of a face image, row 0 uploaded first, sits at s = (x + 0.5) / size,
// t = (y + 0.5) / size: the PNG rows are uploaded top first with no flip.
glm::vec3 cube_direction(CubeFace face, float s, float t);

// The inverse: the face the GL spec selects for a direction (major axis) and (s, t) on it.
struct FaceCoord {
  CubeFace face;
  float s, t;
};
FaceCoord cube_face_coord(const glm::vec3& direction);

// Sky radiance (sRGB, each channel in [0, 1]) seen along a direction; +y is up.
glm::vec3 sky_color(const glm::vec3& direction);
// One face of the sky cube map (RGB, size x size).
Image make_sky_face(CubeFace face, int size);

// Writes a PNG; throws std::runtime_error naming the file when it cannot.
void write_png(const Image& image, const std::filesystem::path& path);

}  // namespace clothsim::texgen

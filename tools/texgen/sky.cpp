// The sky cube map: a horizon-to-zenith gradient, a sun disc with glow, and a darker ground
// with a grid below the horizon, fading into haze. Face texels are placed with the GL spec's
// cube map face selection table (OpenGL 4.6 §8.13, table 8.19), so adjacent faces meet with no
// seam when the PNGs are uploaded top row first to GL_TEXTURE_CUBE_MAP_POSITIVE_X + face.
#include <cmath>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "texgen.hpp"
#include "texgen_detail.hpp"

namespace clothsim::texgen {

std::string face_name(CubeFace face) {
  static const char* names[6] = {"posx", "negx", "posy", "negy", "posz", "negz"};
  return names[int(face)];
}

// Table 8.19 gives (sc, tc, ma) per face with s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2;
// here it is solved for the direction with |ma| = 1.
glm::vec3 cube_direction(CubeFace face, float s, float t) {
  const float sc = 2 * s - 1, tc = 2 * t - 1;
  switch (face) {
    case CubeFace::PosX: return {1, -tc, -sc};   // sc = -rz, tc = -ry
    case CubeFace::NegX: return {-1, -tc, sc};   // sc = +rz, tc = -ry
    case CubeFace::PosY: return {sc, 1, tc};     // sc = +rx, tc = +rz
    case CubeFace::NegY: return {sc, -1, -tc};   // sc = +rx, tc = -rz
    case CubeFace::PosZ: return {sc, -tc, 1};    // sc = +rx, tc = -ry
    case CubeFace::NegZ: return {-sc, -tc, -1};  // sc = -rx, tc = -ry
  }
  throw std::logic_error("cube_direction: bad face");
}

FaceCoord cube_face_coord(const glm::vec3& d) {
  const glm::vec3 m = glm::abs(d);
  CubeFace face;
  float sc, tc, ma;
  if (m.x >= m.y && m.x >= m.z) {
    face = d.x >= 0 ? CubeFace::PosX : CubeFace::NegX;
    sc = d.x >= 0 ? -d.z : d.z, tc = -d.y, ma = m.x;
  } else if (m.y >= m.z) {
    face = d.y >= 0 ? CubeFace::PosY : CubeFace::NegY;
    sc = d.x, tc = d.y >= 0 ? d.z : -d.z, ma = m.y;
  } else {
    face = d.z >= 0 ? CubeFace::PosZ : CubeFace::NegZ;
    sc = d.z >= 0 ? d.x : -d.x, tc = -d.y, ma = m.z;
  }
  return {face, 0.5f * (sc / ma + 1), 0.5f * (tc / ma + 1)};
}

glm::vec3 sky_color(const glm::vec3& direction) {
  const glm::vec3 d = glm::normalize(direction);
  const glm::vec3 horizon(0.80f, 0.87f, 0.94f), zenith(0.15f, 0.35f, 0.74f);
  glm::vec3 c;
  if (d.y >= 0) {
    c = glm::mix(horizon, zenith, std::pow(d.y, 0.55f));
  } else {
    // Ground plane one unit below the eye, with a one-unit grid offset by half a cell so no line
    // runs along a cube edge; the grid fades with distance (where it would alias) and
    // everything fades into haze, reaching the horizon colour at y = 0.
    const float px = d.x / -d.y + 0.5f, pz = d.z / -d.y + 0.5f;
    const float dist = 1 / -d.y;  // to the ground point (d has unit length)
    const float gx = std::abs(px - std::round(px)), gz = std::abs(pz - std::round(pz));
    const float on_line = 1 - glm::smoothstep(0.015f, 0.025f, std::min(gx, gz));
    const glm::vec3 ground(0.25f, 0.24f, 0.22f), line(0.42f, 0.41f, 0.38f);
    const glm::vec3 g = glm::mix(ground, line, on_line * std::exp(-dist / 6));
    c = glm::mix(horizon, g, std::exp(-dist * 0.08f));
  }
  // The sun sits where the renderer's point light is (above, behind and beside the camera).
  const glm::vec3 sun = glm::normalize(glm::vec3(0.6f, 1.4f, 0.9f));
  const float cos_angle = std::max(glm::dot(d, sun), 0.0f);
  const glm::vec3 warm(1.0f, 0.93f, 0.78f);
  c += warm * (0.45f * std::pow(cos_angle, 400.0f) + 0.18f * std::pow(cos_angle, 24.0f));
  const float radius = 0.035f;  // radians; larger than the real sun so mirrors show it
  const float disc = glm::smoothstep(std::cos(radius * 1.2f), std::cos(radius), cos_angle);
  return glm::clamp(glm::mix(c, glm::vec3(1.0f, 0.98f, 0.92f), disc), 0.0f, 1.0f);
}

Image make_sky_face(CubeFace face, int size) {
  auto color = [face](float s, float t) { return sky_color(cube_direction(face, s, t)); };
  return detail::quantize(size, detail::supersample(size, color), 3);
}

}  // namespace clothsim::texgen

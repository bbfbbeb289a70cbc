// Textures and an offscreen render target, RAII like objects.hpp.
#pragma once

#include <glad/gl.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "objects.hpp"

namespace clothsim::gl {

namespace detail {
void delete_texture(GLuint id);
void delete_framebuffer(GLuint id);
void delete_renderbuffer(GLuint id);
}  // namespace detail

// How a texture is sampled when it is minified. The defaults are what every picture wants; the
// aliasing test turns them off to show what they prevent.
struct TextureFiltering {
  bool mipmaps = true;          // trilinear (GL_LINEAR_MIPMAP_LINEAR) rather than GL_LINEAR
  float max_anisotropy = 16.f;  // capped by the driver; 1 = isotropic
};

// The anisotropy the driver allows (GL 4.6 core or GL_EXT/ARB_texture_filter_anisotropic),
// or 1 when it has neither.
float max_texture_anisotropy();

class Texture {
 public:
  // A 2D RGBA8 texture from a PNG (repeating); throws std::runtime_error naming the file.
  static Texture load_2d(const std::filesystem::path& png, const TextureFiltering& filtering = {});
  // A cube map from six PNGs in GL face order +x, -x, +y, -y, +z, -z (mipmapped).
  static Texture load_cube(const std::array<std::filesystem::path, 6>& faces,
                           const TextureFiltering& filtering = {});
  // A 2D texture of one level to draw into (a shadow map, a depth pre-pass, an occlusion
  // buffer) in `internal_format`, e.g. GL_DEPTH_COMPONENT32F or GL_R8; clamped to its edge,
  // filtered linearly or not. Throws std::runtime_error naming `label` if the driver refuses.
  static Texture target_2d(GLenum internal_format, int width, int height, bool linear, std::string_view label);
  void bind(GLuint unit) const;
  int width() const { return width_; }
  int height() const { return height_; }
  GLuint id() const { return name_.get(); }  // for Framebuffer::attach

 private:
  Texture(GLenum target);
  detail::Name<detail::delete_texture> name_;
  GLenum target_;
  int width_ = 0, height_ = 0;
};

// A read-only texel view of a Buffer (GL_TEXTURE_BUFFER), same memory, no copy. Compute
// passes read particle data through these with texelFetch: drivers serve texel fetches from
// the texture path (on llvmpipe a vectorised gather instead of a per-lane loop, 2-3x fewer
// instructions per read), while writes stay on the storage-buffer binding of the same buffer.
// Reads after shader writes need glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT).
class BufferTexture {
 public:
  explicit BufferTexture(std::string_view label = {});
  // (Re)points the view at `buffer` as texels of `format` (e.g. GL_RGBA32F, GL_R32UI); call
  // again after the buffer is reallocated.
  void attach(const Buffer& buffer, GLenum format);
  void bind(GLuint unit) const;

 private:
  detail::Name<detail::delete_texture> name_;
};

// A framebuffer object drawing into textures (the renderer's shadow and occlusion passes).
class Framebuffer {
 public:
  explicit Framebuffer(std::string_view label = {});
  // Attaches level 0 of `texture` at `attachment` (GL_DEPTH_ATTACHMENT, GL_COLOR_ATTACHMENT0),
  // then throws std::runtime_error naming the label if the framebuffer is not complete.
  void attach(GLenum attachment, const Texture& texture);
  void bind() const;  // as GL_FRAMEBUFFER, with the viewport set to the attachments' size

 private:
  detail::Name<detail::delete_framebuffer> name_;
  std::string label_;
  int width_ = 0, height_ = 0;
  bool has_colour_ = false;
};

// A sampler object: how a texture unit reads, whatever texture is bound there. The shadow
// map is read two ways at once, compared (PCF) and raw (the blocker search), through two of these.
class Sampler {
 public:
  // compare: GL_COMPARE_REF_TO_TEXTURE with GL_LEQUAL, for a sampler2DShadow. Outside [0, 1]
  // the border reads `border` (1 = far: lit).
  Sampler(bool linear, bool compare, float border);
  void bind(GLuint unit) const;

 private:
  static void delete_sampler(GLuint id);
  detail::Name<delete_sampler> name_;
};

// An offscreen colour + depth target for headless rendering and screenshots: multisampled
// (resolved on read-back) when samples > 1, plain when samples is 1.
class RenderTarget {
 public:
  // Throws std::runtime_error when the driver cannot make it (e.g. more than GL_MAX_SAMPLES).
  RenderTarget(int width, int height, int samples = 4);
  void bind() const;  // as the draw framebuffer, with the viewport set
  // Resolves and reads RGBA8, top row first (ready for an image file).
  std::vector<uint8_t> read_rgba() const;
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

 private:
  int width_, height_, samples_;
  detail::Name<detail::delete_framebuffer> msaa_fbo_, resolve_fbo_;
  detail::Name<detail::delete_renderbuffer> msaa_color_, msaa_depth_, resolve_color_;
};

}  // namespace clothsim::gl

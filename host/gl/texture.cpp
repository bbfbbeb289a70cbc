#include "texture.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>
#include <stb/stb_image.h>

#include "io/input_file.hpp"  // clothsim_core

namespace clothsim::gl {

void detail::delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void detail::delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void detail::delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }

namespace {

GLuint new_texture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return id;
}

}  // namespace

BufferTexture::BufferTexture(std::string_view label) : name_(new_texture()) {
  // A texture name becomes an object on first bind; only then can it carry a label.
  glBindTexture(GL_TEXTURE_BUFFER, name_.get());
  if (!label.empty()) glObjectLabel(GL_TEXTURE, name_.get(), GLsizei(label.size()), label.data());
}

void BufferTexture::attach(const Buffer& buffer, GLenum format) {
  glBindTexture(GL_TEXTURE_BUFFER, name_.get());
  glTexBuffer(GL_TEXTURE_BUFFER, format, buffer.id());
}

void BufferTexture::bind(GLuint unit) const {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_BUFFER, name_.get());
}

namespace {

struct Image {
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
};

Image read_png(const std::filesystem::path& path) {
  Image im;
  int channels = 0;
  // stat first: stb would block on a FIFO or read a device without end.
  if (auto problem = input_file_problem(path))
    throw std::runtime_error(fmt::format("{}: cannot load the image: {}", printable(path.string()), *problem));
  stbi_uc* data = stbi_load(path.string().c_str(), &im.w, &im.h, &channels, 4);
  if (!data)
    throw std::runtime_error(fmt::format("{}: cannot load the image ({})", path.string(), stbi_failure_reason()));
  im.rgba.assign(data, data + size_t(im.w) * im.h * 4);
  stbi_image_free(data);
  return im;
}

GLuint gen(void (*f)(GLsizei, GLuint*)) {
  GLuint id = 0;
  f(1, &id);
  return id;
}

// samples 0 is a plain (single-sample) renderbuffer.
GLuint new_renderbuffer(GLenum format, int w, int h, int samples) {
  GLuint id = gen(glGenRenderbuffers);
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, w, h);
  return id;
}

// The loader is generated for GL 4.3 core, which predates anisotropic filtering; the EXT, the
// ARB extension and GL 4.6 core share these two enums.
constexpr GLenum kTextureMaxAnisotropy = 0x84FE, kMaxTextureMaxAnisotropy = 0x84FF;

bool has_extension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))); e && !std::strcmp(e, name))
      return true;
  return false;
}

// Mipmaps and anisotropy for the bound texture of `target`, whose level 0 is uploaded.
void set_minification(GLenum target, const TextureFiltering& filtering) {
  if (filtering.mipmaps) glGenerateMipmap(target);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filtering.mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  // Cloth seen at a grazing angle is minified far more along one axis than the other: a
  // trilinear lookup blurs it to the coarser one, anisotropic filtering keeps the weave.
  const float anisotropy = std::min(filtering.max_anisotropy, max_texture_anisotropy());
  if (anisotropy > 1.f) glTexParameterf(target, kTextureMaxAnisotropy, anisotropy);
}

// Checked before any storage is made, so the message says what to change rather than that a
// framebuffer is incomplete.
int checked_samples(int samples) {
  GLint max = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max);
  if (samples > max)
    throw std::runtime_error(fmt::format("{} samples per pixel: this OpenGL driver allows at most {} (GL_MAX_SAMPLES)",
                                         samples, max));
  return std::max(samples, 1);
}

}  // namespace

float max_texture_anisotropy() {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  const bool core = major > 4 || (major == 4 && minor >= 6);
  if (!core && !has_extension("GL_EXT_texture_filter_anisotropic") && !has_extension("GL_ARB_texture_filter_anisotropic"))
    return 1.f;
  GLfloat max = 1.f;
  glGetFloatv(kMaxTextureMaxAnisotropy, &max);
  return std::max(max, 1.f);
}

Texture::Texture(GLenum target) : name_(gen(glGenTextures)), target_(target) {}

void Texture::bind(GLuint unit) const {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(target_, name_.get());
}

Texture Texture::target_2d(GLenum internal_format, int width, int height, bool linear, std::string_view label) {
  Texture t(GL_TEXTURE_2D);
  t.width_ = width;
  t.height_ = height;
  glBindTexture(GL_TEXTURE_2D, t.name_.get());
  if (!label.empty()) glObjectLabel(GL_TEXTURE, t.name_.get(), GLsizei(label.size()), label.data());
  while (glGetError() != GL_NO_ERROR) {
  }
  glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR)
    throw std::runtime_error(fmt::format("{}: cannot make a {}x{} texture (GL error 0x{:x})", label, width, height, e));
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

namespace {
// Keeps the caller's framebuffers bound across a scope that binds another (made while the
// caller is drawing, e.g. on its first frame, a framebuffer must not take over its target).
struct KeepFramebuffers {
  GLint draw = 0, read = 0;
  KeepFramebuffers() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  }
  ~KeepFramebuffers() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read));
  }
};
}  // namespace

Framebuffer::Framebuffer(std::string_view label) : name_(gen(glGenFramebuffers)), label_(label) {
  KeepFramebuffers keep;
  glBindFramebuffer(GL_FRAMEBUFFER, name_.get());
  if (!label.empty()) glObjectLabel(GL_FRAMEBUFFER, name_.get(), GLsizei(label.size()), label.data());
}

void Framebuffer::attach(GLenum attachment, const Texture& texture) {
  KeepFramebuffers keep;
  glBindFramebuffer(GL_FRAMEBUFFER, name_.get());
  glFramebufferTexture(GL_FRAMEBUFFER, attachment, texture.id(), 0);
  width_ = texture.width();
  height_ = texture.height();
  has_colour_ = has_colour_ || attachment != GL_DEPTH_ATTACHMENT;
  // A depth-only framebuffer draws no colour; without saying so it is incomplete.
  const GLenum none = GL_NONE, colour = GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, has_colour_ ? &colour : &none);
  glReadBuffer(has_colour_ ? GL_COLOR_ATTACHMENT0 : GL_NONE);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error(fmt::format("{}: framebuffer incomplete (status 0x{:x})", label_, status));
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, name_.get());
  glViewport(0, 0, width_, height_);
}

void Sampler::delete_sampler(GLuint id) { glDeleteSamplers(1, &id); }

Sampler::Sampler(bool linear, bool compare, float border) : name_(gen(glGenSamplers)) {
  const GLuint s = name_.get();
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, filter);
  glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, filter);
  glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float colour[4] = {border, border, border, border};
  glSamplerParameterfv(s, GL_TEXTURE_BORDER_COLOR, colour);
  if (compare) {
    glSamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(s, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }
}

void Sampler::bind(GLuint unit) const { glBindSampler(unit, name_.get()); }

Texture Texture::load_2d(const std::filesystem::path& png, const TextureFiltering& filtering) {
  Image im = read_png(png);
  Texture t(GL_TEXTURE_2D);
  t.width_ = im.w;
  t.height_ = im.h;
  glBindTexture(GL_TEXTURE_2D, t.name_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, im.w, im.h, 0, GL_RGBA, GL_UNSIGNED_BYTE, im.rgba.data());
  set_minification(GL_TEXTURE_2D, filtering);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

Texture Texture::load_cube(const std::array<std::filesystem::path, 6>& faces, const TextureFiltering& filtering) {
  Texture t(GL_TEXTURE_CUBE_MAP);
  glBindTexture(GL_TEXTURE_CUBE_MAP, t.name_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int f = 0; f < 6; ++f) {
    Image im = read_png(faces[f]);
    t.width_ = im.w;
    t.height_ = im.h;
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, GL_RGBA8, im.w, im.h, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 im.rgba.data());
  }
  // Mirror minifies the sky a lot on a folded cloth: without mipmaps the ground grid in the
  // cube map aliases into sparkles.
  set_minification(GL_TEXTURE_CUBE_MAP, filtering);
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, w, GL_CLAMP_TO_EDGE);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  return t;
}

RenderTarget::RenderTarget(int w, int h, int samples)
    : width_(w), height_(h), samples_(checked_samples(samples)), msaa_fbo_(gen(glGenFramebuffers)),
      resolve_fbo_(gen(glGenFramebuffers)),
      msaa_color_(new_renderbuffer(GL_RGBA8, w, h, samples_ > 1 ? samples_ : 0)),
      msaa_depth_(new_renderbuffer(GL_DEPTH_COMPONENT24, w, h, samples_ > 1 ? samples_ : 0)),
      resolve_color_(new_renderbuffer(GL_RGBA8, w, h, 0)) {
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_.get());
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error(fmt::format("offscreen framebuffer {}x{} ({} samples) is incomplete", w, h, samples_));
  glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color_.get());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_.get());
  glViewport(0, 0, width_, height_);
}

std::vector<uint8_t> RenderTarget::read_rgba() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.get());
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.get());
  std::vector<uint8_t> rows(size_t(width_) * height_ * 4), flipped(rows.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  const size_t stride = size_t(width_) * 4;
  // GL's first row is the bottom one; image files start at the top.
  for (int y = 0; y < height_; ++y)
    std::copy_n(rows.data() + size_t(height_ - 1 - y) * stride, stride, flipped.data() + size_t(y) * stride);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return flipped;
}

}  // namespace clothsim::gl

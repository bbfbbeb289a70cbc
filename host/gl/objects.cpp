#include "objects.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "debug_output.hpp"

namespace clothsim::gl {

void detail::delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void detail::delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }

namespace {

GLuint new_buffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  // glGen* only reserves a name; the first bind creates the object (so it can be labelled).
  glBindBuffer(GL_COPY_WRITE_BUFFER, id);
  return id;
}

GLuint new_vertex_array() {
  GLint previous = 0;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previous);
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  glBindVertexArray(id);
  glBindVertexArray(GLuint(previous));
  return id;
}

void set_label(GLenum identifier, GLuint id, std::string_view text) {
  if (!text.empty()) glObjectLabel(identifier, id, GLsizei(text.size()), text.data());
}

void check_range(std::string_view what, std::size_t offset, std::size_t bytes, std::size_t size) {
  if (offset > size || bytes > size - offset) {
    throw std::out_of_range(
        fmt::format("Buffer::{}: bytes [{}, {}) outside a buffer of {} bytes", what, offset, offset + bytes, size));
  }
}

}  // namespace

Buffer::Buffer(std::string_view label_text) : name_(new_buffer()), label_(label_text) {
  set_label(GL_BUFFER, name_.get(), label_text);
}

void Buffer::allocate(std::size_t bytes, const void* data, GLenum usage) {
  glBindBuffer(GL_COPY_WRITE_BUFFER, name_.get());
  auto name = [&] {
    return label_.empty() ? std::string("an unnamed buffer") : fmt::format("the buffer '{}'", label_);
  };
  // An earlier command's GL_OUT_OF_MEMORY is reported as such, not blamed on this buffer.
  if (poll_out_of_memory())
    throw OutOfMemoryError(fmt::format("GL_OUT_OF_MEMORY: the GPU driver ran out of memory (found before "
                                       "allocating {})", name()));
  glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(bytes), data, usage);
  if (poll_out_of_memory()) {
    size_ = 0;
    throw OutOfMemoryError(fmt::format("GL_OUT_OF_MEMORY: the GPU driver could not allocate {} bytes ({:.1f} MiB) "
                                       "for {}",
                                       bytes, double(bytes) / 1048576.0, name()));
  }
  size_ = bytes;
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) {
  check_range("upload", offset, bytes, size_);
  glBindBuffer(GL_COPY_WRITE_BUFFER, name_.get());
  glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::download(std::size_t offset, std::size_t bytes, void* dst) const {
  check_range("download", offset, bytes, size_);
  glBindBuffer(GL_COPY_READ_BUFFER, name_.get());
  glGetBufferSubData(GL_COPY_READ_BUFFER, GLintptr(offset), GLsizeiptr(bytes), dst);
}

void Buffer::clear_to_zero() {
  glBindBuffer(GL_COPY_WRITE_BUFFER, name_.get());
  // Null data means zero; R8UI makes any byte size valid.
  glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, nullptr);
}

void Buffer::copy_from(const Buffer& src, std::size_t src_offset, std::size_t dst_offset, std::size_t bytes) {
  check_range("copy_from (source)", src_offset, bytes, src.size_);
  check_range("copy_from (destination)", dst_offset, bytes, size_);
  glBindBuffer(GL_COPY_READ_BUFFER, src.name_.get());
  glBindBuffer(GL_COPY_WRITE_BUFFER, name_.get());
  glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, GLintptr(src_offset), GLintptr(dst_offset),
                      GLsizeiptr(bytes));
}

void Buffer::bind_base(GLenum target, GLuint binding) const { glBindBufferBase(target, binding, name_.get()); }

void Buffer::bind(GLenum target) const { glBindBuffer(target, name_.get()); }

Fence Fence::insert() {
  Fence f;
  f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  return f;
}

bool Fence::signalled() const {
  if (!sync_) return true;
  const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  if (r == GL_WAIT_FAILED) throw std::runtime_error("glClientWaitSync failed on a fence");
  return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

void Fence::wait() const {
  if (!sync_) return;
  for (;;) {
    // One second at a time: a GPU frame never takes that long unless the driver is stuck.
    const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
    if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) return;
    if (r == GL_WAIT_FAILED) throw std::runtime_error("glClientWaitSync failed on a fence");
  }
}

void Fence::reset() {
  if (sync_) glDeleteSync(sync_);
  sync_ = nullptr;
}

VertexArray::VertexArray(std::string_view label_text) : name_(new_vertex_array()) {
  set_label(GL_VERTEX_ARRAY, name_.get(), label_text);
}

void VertexArray::bind() const { glBindVertexArray(name_.get()); }

void VertexArray::set_element_buffer(const Buffer& indices) {
  bind();
  indices.bind(GL_ELEMENT_ARRAY_BUFFER);
}

}  // namespace clothsim::gl

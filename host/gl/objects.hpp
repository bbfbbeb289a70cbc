// Move-only owners of GL objects: the name is created with the object and deleted with it,
// and no raw GL name leaves these classes. Needs a current context (see context.hpp).
// Include this (or <glad/gl.h>) before any other GL header; GLFW needs GLFW_INCLUDE_NONE.
#pragma once

#include <glad/gl.h>

#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace clothsim::gl {

namespace detail {
// Owns one GL name; Delete is the matching glDelete* wrapper.
template <void (*Delete)(GLuint)> class Name {
 public:
  explicit Name(GLuint id = 0) : id_(id) {}
  Name(Name&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Name& operator=(Name&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  ~Name() { reset(); }
  GLuint get() const { return id_; }

 private:
  void reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }
  GLuint id_;
};
void delete_buffer(GLuint id);
void delete_vertex_array(GLuint id);
}  // namespace detail

// The driver said GL_OUT_OF_MEMORY: when allocating a buffer (the message names it and the
// size), or during a run (check_gl_errors, debug_output.hpp: the GPU simulator checks once per
// frame; the divergence guard's read-back checks too).
struct OutOfMemoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A GL buffer object. Uploads and read-backs go through the GL_COPY_*_BUFFER targets, so
// they never disturb the bindings a pass has set up.
class Buffer {
 public:
  // label names the buffer in KHR_debug messages and GPU debuggers.
  explicit Buffer(std::string_view label = {});

  // Replaces the storage with `bytes` bytes, initialised from data (undefined if null).
  // Throws OutOfMemoryError naming the buffer and the size when the driver has no room.
  void allocate(std::size_t bytes, const void* data = nullptr, GLenum usage = GL_DYNAMIC_DRAW);
  void upload(std::size_t offset, std::size_t bytes, const void* data);
  // Reads back: a shader write needs glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT) first.
  void download(std::size_t offset, std::size_t bytes, void* dst) const;
  // Sets every byte to zero (counters, hash tables).
  void clear_to_zero();
  void copy_from(const Buffer& src, std::size_t src_offset, std::size_t dst_offset, std::size_t bytes);

  // Binds the whole buffer at an indexed binding: GL_SHADER_STORAGE_BUFFER or GL_UNIFORM_BUFFER.
  void bind_base(GLenum target, GLuint binding) const;
  // Binds to a non-indexed target, e.g. GL_ELEMENT_ARRAY_BUFFER or GL_DISPATCH_INDIRECT_BUFFER.
  void bind(GLenum target) const;
  std::size_t size() const { return size_; }
  GLuint id() const { return name_.get(); }  // for views of it (BufferTexture) and introspection
  const std::string& label() const { return label_; }

 private:
  detail::Name<detail::delete_buffer> name_;
  std::size_t size_ = 0;
  std::string label_;
};

// Replaces the buffer's storage with the contents of `values`.
template <class T> void upload_vector(Buffer& buffer, std::span<const T> values, GLenum usage = GL_DYNAMIC_DRAW) {
  static_assert(std::is_trivially_copyable_v<T>, "only plain data can be copied to the GPU");
  buffer.allocate(values.size_bytes(), values.data(), usage);
}
template <class T> void upload_vector(Buffer& buffer, const std::vector<T>& values, GLenum usage = GL_DYNAMIC_DRAW) {
  upload_vector(buffer, std::span<const T>(values), usage);
}

// Reads `count` elements of type T starting at element `first`; by default the whole buffer.
template <class T> std::vector<T> download_vector(const Buffer& buffer, std::size_t first = 0,
                                                  std::size_t count = std::size_t(-1)) {
  static_assert(std::is_trivially_copyable_v<T>, "only plain data can be copied from the GPU");
  const std::size_t total = buffer.size() / sizeof(T);
  if (count == std::size_t(-1)) count = first <= total ? total - first : 0;
  std::vector<T> values(count);
  buffer.download(first * sizeof(T), count * sizeof(T), values.data());
  return values;
}

// A fence after every command issued so far (glFenceSync), to learn without stalling when
// the GPU has finished them. Empty when default-constructed.
class Fence {
 public:
  Fence() = default;
  static Fence insert();
  Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}
  Fence& operator=(Fence&& other) noexcept {
    if (this != &other) {
      reset();
      sync_ = std::exchange(other.sync_, nullptr);
    }
    return *this;
  }
  ~Fence() { reset(); }
  explicit operator bool() const { return sync_ != nullptr; }
  // Whether the commands before the fence are done, without waiting. Flushes them, so a
  // fence that is polled will signal.
  bool signalled() const;
  // Waits until they are done (true at once for an empty fence).
  void wait() const;

 private:
  void reset();
  GLsync sync_ = nullptr;
};

// A vertex array object. The renderer pulls vertices from storage buffers by gl_VertexID,
// so it has no attributes; core profile still needs one bound to draw.
class VertexArray {
 public:
  explicit VertexArray(std::string_view label = {});
  void bind() const;
  // Records `indices` as this VAO's GL_ELEMENT_ARRAY_BUFFER (and leaves the VAO bound).
  void set_element_buffer(const Buffer& indices);

 private:
  detail::Name<detail::delete_vertex_array> name_;
};

}  // namespace clothsim::gl

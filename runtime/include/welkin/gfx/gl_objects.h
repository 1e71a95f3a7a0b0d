#pragma once
// Owning wrappers of GL objects (move-only, deleted with their owner) and texture descriptions.
#include <epoxy/gl.h>

#include <initializer_list>

#include <string>
#include <utility>

namespace welkin {

// A GL name with its deleter; move-only.
template <void (*Delete)(GLuint)> class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace gl_delete {
inline void texture(GLuint id) { glDeleteTextures(1, &id); }
inline void buffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void program(GLuint id) { glDeleteProgram(id); }
inline void vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void query(GLuint id) { glDeleteQueries(1, &id); }
}  // namespace gl_delete

using GlTextureName = GlHandle<gl_delete::texture>;
using GlBufferName = GlHandle<gl_delete::buffer>;
using GlFramebufferName = GlHandle<gl_delete::framebuffer>;
using GlProgramName = GlHandle<gl_delete::program>;
using GlVertexArrayName = GlHandle<gl_delete::vertex_array>;
using GlQueryName = GlHandle<gl_delete::query>;

enum class TextureFormat { rgba8, rgba16f, rgba32f, rgba32ui, r8, r32f, rg32f, depth32f };
GLenum gl_internal_format(TextureFormat f);
const char* texture_format_name(TextureFormat f);

struct TextureDesc {
  int width = 1, height = 1, depth = 1;  // depth > 1 makes a 3D texture
  bool array = false;  // with depth > 1: an array of 2D layers instead (filtered within a layer only)
  TextureFormat format = TextureFormat::rgba16f;
  bool linear_filter = true;
  bool clamp = true;
  bool mipmaps = false;  // a full chain, filtered trilinearly (fill it with glGenerateTextureMipmap)
  friend bool operator==(const TextureDesc&, const TextureDesc&) = default;
};

class Texture {
 public:
  Texture() = default;
  explicit Texture(const TextureDesc& desc);
  const TextureDesc& desc() const { return desc_; }
  GLuint id() const { return name_.id(); }
  GLenum target() const {
    return desc_.depth > 1 ? (desc_.array ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_3D) : GL_TEXTURE_2D;
  }
  bool is_3d() const { return desc_.depth > 1; }  // layered: a 3D texture or a 2D array
  explicit operator bool() const { return bool(name_); }

 private:
  TextureDesc desc_;
  GlTextureName name_;
};

// Copies level 0 of a 2D texture into another of the same size and format (what a pass keeps of
// an earlier frame, and puts back).
void copy_texture(const Texture& from, const Texture& to);

// Framebuffer with one colour attachment (or several, drawn to by location) and an optional depth
// attachment.
class Framebuffer {
 public:
  Framebuffer() = default;
  Framebuffer(const Texture* color, const Texture* depth);
  Framebuffer(std::initializer_list<const Texture*> colors, const Texture* depth);
  void bind() const;
  GLuint id() const { return name_.id(); }

 private:
  void attach(const Texture* const* colors, int color_count, const Texture* depth);
  GlFramebufferName name_;
  int width_ = 0, height_ = 0;
};

class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(size_t bytes, const void* data = nullptr);
  void upload(const void* data, size_t bytes, size_t offset = 0);
  GLuint id() const { return name_.id(); }
  size_t size() const { return size_; }

 private:
  GlBufferName name_;
  size_t size_ = 0;
};

// Throws Error naming `where` if GL reported an error.
void check_gl(const char* where);

}  // namespace welkin

#include "welkin/gfx/gl_objects.h"

#include <algorithm>

#include "welkin/core/error.h"

namespace welkin {

GLenum gl_internal_format(TextureFormat f) {
  switch (f) {
    case TextureFormat::rgba8: return GL_RGBA8;
    case TextureFormat::rgba16f: return GL_RGBA16F;
    case TextureFormat::rgba32f: return GL_RGBA32F;
    case TextureFormat::rgba32ui: return GL_RGBA32UI;
    case TextureFormat::r8: return GL_R8;
    case TextureFormat::r32f: return GL_R32F;
    case TextureFormat::rg32f: return GL_RG32F;
    case TextureFormat::depth32f: return GL_DEPTH_COMPONENT32F;
  }
  return GL_RGBA8;
}

const char* texture_format_name(TextureFormat f) {
  switch (f) {
    case TextureFormat::rgba8: return "rgba8";
    case TextureFormat::rgba16f: return "rgba16f";
    case TextureFormat::rgba32f: return "rgba32f";
    case TextureFormat::rgba32ui: return "rgba32ui";
    case TextureFormat::r8: return "r8";
    case TextureFormat::r32f: return "r32f";
    case TextureFormat::rg32f: return "rg32f";
    case TextureFormat::depth32f: return "depth32f";
  }
  return "?";
}

Texture::Texture(const TextureDesc& desc) : desc_(desc) {
  GLuint id = 0;
  glCreateTextures(target(), 1, &id);
  name_ = GlTextureName(id);
  int levels = 1;
  if (desc.mipmaps)
    while ((std::max({desc.width, desc.height, is_3d() ? desc.depth : 1}) >> levels) > 0) ++levels;
  if (is_3d())
    glTextureStorage3D(id, levels, gl_internal_format(desc.format), desc.width, desc.height, desc.depth);
  else
    glTextureStorage2D(id, levels, gl_internal_format(desc.format), desc.width, desc.height);
  GLint filter = desc.linear_filter ? GL_LINEAR : GL_NEAREST;
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER,
                      desc.mipmaps && desc.linear_filter ? GL_LINEAR_MIPMAP_LINEAR : filter);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
  GLint wrap = desc.clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT;
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, wrap);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, wrap);
  glTextureParameteri(id, GL_TEXTURE_WRAP_R, wrap);
  check_gl("texture creation");
}

void copy_texture(const Texture& from, const Texture& to) {
  glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                     to.desc().width, to.desc().height, 1);
}

Framebuffer::Framebuffer(const Texture* color, const Texture* depth) {
  const Texture* colors[1] = {color};
  attach(colors, color ? 1 : 0, depth);
}

Framebuffer::Framebuffer(std::initializer_list<const Texture*> colors, const Texture* depth) {
  attach(colors.begin(), int(colors.size()), depth);
}

void Framebuffer::attach(const Texture* const* colors, int color_count, const Texture* depth) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  name_ = GlFramebufferName(id);
  GLenum buffers[8];
  GLsizei count = 0;
  if (color_count > 8) throw Error("a framebuffer holds at most 8 colour attachments");
  for (int i = 0; i < color_count; ++i) {
    const Texture* color = colors[i];
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0 + GLenum(count), color->id(), 0);
    buffers[count] = GL_COLOR_ATTACHMENT0 + GLenum(count);
    ++count;
    width_ = color->desc().width;
    height_ = color->desc().height;
  }
  if (count == 0) glNamedFramebufferDrawBuffer(id, GL_NONE);
  else glNamedFramebufferDrawBuffers(id, count, buffers);
  if (depth) {
    glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth->id(), 0);
    width_ = depth->desc().width;
    height_ = depth->desc().height;
  }
  GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw Error("framebuffer incomplete (status " + std::to_string(status) + ")");
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, name_.id());
  glViewport(0, 0, width_, height_);
}

Buffer::Buffer(size_t bytes, const void* data) : size_(bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  name_ = GlBufferName(id);
  glNamedBufferStorage(id, GLsizeiptr(bytes), data, GL_DYNAMIC_STORAGE_BIT);
}

void Buffer::upload(const void* data, size_t bytes, size_t offset) {
  if (offset + bytes > size_) throw Error("buffer upload past the end of the buffer");
  glNamedBufferSubData(name_.id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

void check_gl(const char* where) {
  GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw Error(std::string("OpenGL error 0x") + std::to_string(e) + " in " + where);
}

}  // namespace welkin

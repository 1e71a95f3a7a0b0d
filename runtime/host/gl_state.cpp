#include "welkin/host/gl_state.h"

namespace welkin::host {

namespace {

void set_enabled(GLenum cap, GLboolean on) {
  on ? glEnable(cap) : glDisable(cap);
}

void bind_range(GLenum target, GLuint index, GLint buffer, GLint64 start, GLint64 size) {
  // A whole-buffer binding (glBindBufferBase) reads back with size 0.
  if (buffer != 0 && size > 0)
    glBindBufferRange(target, index, GLuint(buffer), GLintptr(start), GLsizeiptr(size));
  else
    glBindBufferBase(target, index, GLuint(buffer));
}

}  // namespace

GlStateGuard::GlStateGuard() {
  save();
}
GlStateGuard::~GlStateGuard() {
  restore();
}

void GlStateGuard::save() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
  blend_ = glIsEnabled(GL_BLEND), depth_test_ = glIsEnabled(GL_DEPTH_TEST),
  stencil_test_ = glIsEnabled(GL_STENCIL_TEST);
  cull_ = glIsEnabled(GL_CULL_FACE), scissor_test_ = glIsEnabled(GL_SCISSOR_TEST);
  polygon_offset_fill_ = glIsEnabled(GL_POLYGON_OFFSET_FILL),
  point_size_ = glIsEnabled(GL_PROGRAM_POINT_SIZE);
  srgb_ = glIsEnabled(GL_FRAMEBUFFER_SRGB);
  glGetIntegerv(GL_BLEND_SRC_RGB, &blend_src_rgb_);
  glGetIntegerv(GL_BLEND_DST_RGB, &blend_dst_rgb_);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_src_alpha_);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_dst_alpha_);
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &blend_eq_rgb_);
  glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blend_eq_alpha_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  glGetFloatv(GL_DEPTH_CLEAR_VALUE, &depth_clear_);
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_.data());
  glGetFloatv(GL_COLOR_CLEAR_VALUE, color_clear_.data());
  glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_);
  glGetIntegerv(GL_FRONT_FACE, &front_face_);
  glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_);
  glGetIntegerv(GL_VIEWPORT, viewport_.data());
  glGetIntegerv(GL_SCISSOR_BOX, scissor_box_.data());
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  glGetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment_);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpack_alignment_);
  for (int u = 0; u < kTextureUnits; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &units_[u].texture_2d);
    glGetIntegerv(GL_TEXTURE_BINDING_3D, &units_[u].texture_3d);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &units_[u].texture_2d_array);
    glGetIntegerv(GL_SAMPLER_BINDING, &units_[u].sampler);
  }
  glActiveTexture(GLenum(active_texture_));
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_buffer_);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_buffer_);
  for (int i = 0; i < kUniformBuffers; ++i) {
    BufferRange& b = uniform_buffers_[i];
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, GLuint(i), &b.buffer);
    glGetInteger64i_v(GL_UNIFORM_BUFFER_START, GLuint(i), &b.start);
    glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, GLuint(i), &b.size);
  }
  for (int i = 0; i < kStorageBuffers; ++i) {
    BufferRange& b = storage_buffers_[i];
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(i), &b.buffer);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, GLuint(i), &b.start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(i), &b.size);
  }
  for (int i = 0; i < kImageUnits; ++i) {
    ImageUnit& m = images_[i];
    glGetIntegeri_v(GL_IMAGE_BINDING_NAME, GLuint(i), &m.texture);
    glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, GLuint(i), &m.level);
    glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, GLuint(i), &m.layered);
    glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, GLuint(i), &m.layer);
    glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, GLuint(i), &m.access);
    glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, GLuint(i), &m.format);
  }
}

void GlStateGuard::restore() const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_fb_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_fb_));
  // A program deleted while current stays current until another is used; Welkin's passes used others,
  // so it is gone now and no program is current, as the host would find after its next use of one.
  glUseProgram(glIsProgram(GLuint(program_)) ? GLuint(program_) : 0);
  glBindVertexArray(GLuint(vao_));
  glBindBuffer(GL_ARRAY_BUFFER, GLuint(array_buffer_));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_buffer_));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack_buffer_));
  set_enabled(GL_BLEND, blend_), set_enabled(GL_DEPTH_TEST, depth_test_),
      set_enabled(GL_STENCIL_TEST, stencil_test_);
  set_enabled(GL_CULL_FACE, cull_), set_enabled(GL_SCISSOR_TEST, scissor_test_);
  set_enabled(GL_POLYGON_OFFSET_FILL, polygon_offset_fill_), set_enabled(GL_PROGRAM_POINT_SIZE, point_size_);
  set_enabled(GL_FRAMEBUFFER_SRGB, srgb_);
  glBlendFuncSeparate(GLenum(blend_src_rgb_), GLenum(blend_dst_rgb_), GLenum(blend_src_alpha_),
                      GLenum(blend_dst_alpha_));
  glBlendEquationSeparate(GLenum(blend_eq_rgb_), GLenum(blend_eq_alpha_));
  glDepthFunc(GLenum(depth_func_));
  glDepthMask(depth_mask_);
  glClearDepth(depth_clear_);
  glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
  glClearColor(color_clear_[0], color_clear_[1], color_clear_[2], color_clear_[3]);
  glCullFace(GLenum(cull_face_));
  glFrontFace(GLenum(front_face_));
  glClipControl(GLenum(clip_origin_), GLenum(clip_depth_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glScissor(scissor_box_[0], scissor_box_[1], scissor_box_[2], scissor_box_[3]);
  for (int u = 0; u < kTextureUnits; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glBindTexture(GL_TEXTURE_2D, GLuint(units_[u].texture_2d));
    glBindTexture(GL_TEXTURE_3D, GLuint(units_[u].texture_3d));
    glBindTexture(GL_TEXTURE_2D_ARRAY, GLuint(units_[u].texture_2d_array));
    glBindSampler(GLuint(u), GLuint(units_[u].sampler));
  }
  glActiveTexture(GLenum(active_texture_));
  glPixelStorei(GL_PACK_ALIGNMENT, pack_alignment_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, unpack_alignment_);
  for (int i = 0; i < kUniformBuffers; ++i) {
    const BufferRange& b = uniform_buffers_[i];
    bind_range(GL_UNIFORM_BUFFER, GLuint(i), b.buffer, b.start, b.size);
  }
  for (int i = 0; i < kStorageBuffers; ++i) {
    const BufferRange& b = storage_buffers_[i];
    bind_range(GL_SHADER_STORAGE_BUFFER, GLuint(i), b.buffer, b.start, b.size);
  }
  // The indexed binds above also set the generic binding points: those last.
  glBindBuffer(GL_UNIFORM_BUFFER, GLuint(uniform_buffer_));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(storage_buffer_));
  for (int i = 0; i < kImageUnits; ++i) {
    const ImageUnit& m = images_[i];
    glBindImageTexture(GLuint(i), GLuint(m.texture), m.level, GLboolean(m.layered), m.layer, GLenum(m.access),
                       GLenum(m.format));
  }
}

}  // namespace welkin::host

#pragma once
// The host program's GL state, saved before Welkin draws and put back after, so that a host finds
// its context as it left it. Saved: the draw and read framebuffers, the program, the vertex array,
// the array and pixel pack/unpack buffers; blending (enable, functions, equations), the depth test,
// function, mask and clear value, the colour mask and clear value, the stencil test, face culling
// (enable, face, winding), polygon offset fill, program point size, framebuffer sRGB; the viewport and
// scissor (test and box); the clip control (origin, depth mode); the active texture unit and the
// 2D, 3D and 2D-array textures and samplers of units 0..15; uniform buffer bindings 0..15, shader
// storage bindings 0..7 and image units 0..7 (with their ranges and formats); pack and unpack alignment.
#include <epoxy/gl.h>

#include <array>

namespace welkin::host {

class GlStateGuard {
 public:
  static constexpr int kTextureUnits = 16, kUniformBuffers = 16, kStorageBuffers = 8, kImageUnits = 8;

  GlStateGuard();   // saves
  ~GlStateGuard();  // restores
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;
  // Puts the saved state back now (the host's, for its geometry drawn in the middle of Welkin's frame).
  void restore() const;

 private:
  struct BufferRange {
    GLint buffer = 0;
    GLint64 start = 0, size = 0;
  };
  struct ImageUnit {
    GLint texture = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY, format = GL_R8;
  };
  void save();

  GLint draw_fb_ = 0, read_fb_ = 0, program_ = 0, vao_ = 0, array_buffer_ = 0, pack_buffer_ = 0,
        unpack_buffer_ = 0;
  GLboolean blend_ = 0, depth_test_ = 0, stencil_test_ = 0, cull_ = 0, scissor_test_ = 0,
            polygon_offset_fill_ = 0, point_size_ = 0, srgb_ = 0, depth_mask_ = 0;
  GLint blend_src_rgb_ = 0, blend_dst_rgb_ = 0, blend_src_alpha_ = 0, blend_dst_alpha_ = 0, blend_eq_rgb_ = 0,
        blend_eq_alpha_ = 0;
  GLint depth_func_ = 0, cull_face_ = 0, front_face_ = 0, clip_origin_ = 0, clip_depth_ = 0;
  GLfloat depth_clear_ = 1.0f;
  std::array<GLboolean, 4> color_mask_{};
  std::array<GLfloat, 4> color_clear_{};
  std::array<GLint, 4> viewport_{}, scissor_box_{};
  GLint active_texture_ = GL_TEXTURE0, pack_alignment_ = 4, unpack_alignment_ = 4;
  struct UnitBindings {
    GLint texture_2d = 0, texture_3d = 0, texture_2d_array = 0, sampler = 0;
  };
  std::array<UnitBindings, kTextureUnits> units_{};
  GLint uniform_buffer_ = 0, storage_buffer_ = 0;
  std::array<BufferRange, kUniformBuffers> uniform_buffers_{};
  std::array<BufferRange, kStorageBuffers> storage_buffers_{};
  std::array<ImageUnit, kImageUnits> images_{};
};

}  // namespace welkin::host

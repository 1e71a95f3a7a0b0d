#include "welkin/gfx/compute.h"

namespace welkin {

bool ensure_texture(std::unique_ptr<Texture>& texture, const TextureDesc& desc) {
  if (texture && texture->desc() == desc) return false;
  texture = std::make_unique<Texture>(desc);
  glClearTexImage(texture->id(), 0, GL_RGBA, GL_FLOAT, nullptr);
  return true;
}

void dispatch_compute(const Program& program, int groups_x, int groups_y, int groups_z) {
  program.use();
  glDispatchCompute(GLuint(groups_x), GLuint(groups_y), GLuint(groups_z));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void dispatch_compute_indirect(const Program& program, const Buffer& commands, size_t offset) {
  program.use();
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, commands.id());
  glDispatchComputeIndirect(GLintptr(offset));
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void bind_image_for_write(GLuint unit, const Texture& texture) {
  glBindImageTexture(unit, texture.id(), 0, texture.is_3d() ? GL_TRUE : GL_FALSE, 0, GL_WRITE_ONLY,
                     gl_internal_format(texture.desc().format));
}

}  // namespace welkin

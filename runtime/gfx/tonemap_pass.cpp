#include "welkin/gfx/tonemap_pass.h"

#include <string>

#include "welkin/gfx/compute.h"
#include "welkin/gfx/shader.h"

namespace welkin {

void run_tonemap(ShaderLibrary& shaders, GLuint empty_vao, const Texture& hdr, const Texture& output,
                 const ToneMap& tm, PassForm form) {
  const int width = output.desc().width, height = output.desc().height;
  const bool upscale = hdr.desc().width != width || hdr.desc().height != height;
  const ShaderDefines defines = {{"TONEMAPPER", std::to_string(tm.tonemapper)},
                                 {"TONEMAP_UPSCALE", upscale ? "1" : "0"}};
  const Program& p = form == PassForm::compute ? shaders.compute("tonemap.comp", defines)
                                               : shaders.graphics("fullscreen.vert", "tonemap.frag", defines);
  glBindTextureUnit(0, hdr.id());
  p.set("u_exposure", tm.exposure);
  if (upscale) p.set("u_output_size", glm::vec2(width, height));
  if (form == PassForm::compute) {
    bind_image_for_write(0, output);
    dispatch_screen(p, PixelRect{0, 0, width, height});
    return;
  }
  Framebuffer fb(&output, nullptr);
  fb.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  p.use();
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace welkin

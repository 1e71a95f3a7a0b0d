#include "gl_bench.h"

#include <chrono>
#include <memory>

#include "welkin/gfx/renderer.h"
#include "welkin/gfx/shader.h"

namespace welkin::bench {

GlContext& context() {
  static std::unique_ptr<GlContext> ctx = create_headless_context();
  return *ctx;
}

double gpu_ms(const std::function<void()>& draw) {
  // Finish before and after: on llvmpipe timestamps are taken at submission, not when work runs.
  glFinish();
  auto t0 = std::chrono::steady_clock::now();
  draw();
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void draw_fullscreen_copy(const Texture& source, const Framebuffer& target) {
  static ShaderLibrary lib = [] {
    ShaderLibrary l;
    l.add_search_dir(runtime_shader_dir());
    return l;
  }();
  static GLuint vao = [] {
    GLuint v;
    glCreateVertexArrays(1, &v);
    return v;
  }();
  const Program& p = lib.graphics("fullscreen.vert", "copy.frag");
  target.bind();
  p.use();
  glBindTextureUnit(0, source.id());
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace welkin::bench

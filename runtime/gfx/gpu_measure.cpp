#include "welkin/gfx/gpu_measure.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "welkin/gfx/shader.h"

namespace welkin {

double finished_ms(const std::function<void()>& work) {
  glFinish();
  auto t0 = std::chrono::steady_clock::now();
  work();
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double fullscreen_copy_floor_ms(ShaderLibrary& shaders, int width, int height, int repeats) {
  Texture src(TextureDesc{.width = width, .height = height}), dst(TextureDesc{.width = width, .height = height});
  Framebuffer fb(&dst, nullptr);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  const Program& p = shaders.graphics("fullscreen.vert", "copy.frag");
  auto copy = [&] {
    fb.bind();
    p.use();
    glBindTextureUnit(0, src.id());
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  };
  finished_ms(copy);  // warm-up: first use compiles and allocates
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i) ms.push_back(finished_ms(copy));
  glDeleteVertexArrays(1, &vao);
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

}  // namespace welkin

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

CopyFloor::CopyFloor(ShaderLibrary& shaders, int width, int height)
    : src_(TextureDesc{.width = width, .height = height}),
      dst_(TextureDesc{.width = width, .height = height}),
      fb_(&dst_, nullptr),
      program_(shaders.graphics("fullscreen.vert", "copy.frag")) {
  glCreateVertexArrays(1, &vao_);
  measure_ms(1);  // warm-up: first use compiles and allocates
}

CopyFloor::~CopyFloor() { glDeleteVertexArrays(1, &vao_); }

double CopyFloor::measure_ms(int repeats) {
  auto copy = [&] {
    fb_.bind();
    program_.use();
    glBindTextureUnit(0, src_.id());
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  };
  std::vector<double> ms;
  for (int i = 0; i < std::max(repeats, 1); ++i) ms.push_back(finished_ms(copy));
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

double fullscreen_copy_floor_ms(ShaderLibrary& shaders, int width, int height, int repeats) {
  return CopyFloor(shaders, width, height).measure_ms(repeats);
}

}  // namespace welkin

#include "welkin/gfx/screen_pass.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/shader.h"
#include "welkin/gfx/tonemap_pass.h"

namespace welkin {

const char* pass_form_name(PassForm form) {
  return form == PassForm::compute ? "compute" : "fragment";
}

PassForm PassForms::of(const std::string& pass) const {
  if (auto it = forced.find(pass); it != forced.end()) return it->second;
  if (auto it = forced.find("*"); it != forced.end()) return it->second;
  return device;
}

void dispatch_screen(const Program& program, const PixelRect& pixels) {
  if (pixels.empty()) return;
  program.use();
  program.set("u_pixel_origin", glm::ivec2(pixels.x0, pixels.y0));
  program.set("u_pixel_end", glm::ivec2(pixels.x1, pixels.y1));
  // The shader's own tile (welkin/screen_pass.glsl's, unless a pass chose another).
  GLint tile[3] = {kScreenTileX, kScreenTileY, 1};
  glGetProgramiv(program.id(), GL_COMPUTE_WORK_GROUP_SIZE, tile);
  glDispatchCompute(GLuint((pixels.x1 - pixels.x0 + tile[0] - 1) / tile[0]),
                    GLuint((pixels.y1 - pixels.y0 + tile[1] - 1) / tile[1]), 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

PixelRect clipped(const PixelRect& r, int width, int height) {
  return {std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, width), std::min(r.y1, height)};
}

void bind_image_read_write(GLuint unit, const Texture& texture) {
  glBindImageTexture(unit, texture.id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                     gl_internal_format(texture.desc().format));
}

const char* image_format_qualifier(TextureFormat format) {
  switch (format) {
    case TextureFormat::rgba8:
      return "rgba8";
    case TextureFormat::rgba16f:
      return "rgba16f";
    case TextureFormat::rgba32f:
      return "rgba32f";
    case TextureFormat::rgba32ui:
      return "rgba32ui";
    case TextureFormat::r8:
      return "r8";
    case TextureFormat::r32f:
      return "r32f";
    case TextureFormat::rg32f:
      return "rg32f";
    case TextureFormat::depth32f:
      break;
  }
  return "r32f";  // depth is never an image; the caller's shader then fails to link, naming the image
}

PassFormProbe probe_pass_form(ShaderLibrary& shaders, int width, int height, int repeats) {
  const Texture hdr(TextureDesc{.width = width, .height = height});
  const Texture output(
      TextureDesc{.width = width, .height = height, .format = TextureFormat::rgba8, .linear_filter = false});
  glClearTexImage(hdr.id(), 0, GL_RGBA, GL_FLOAT, nullptr);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  PassFormProbe probe{.width = width, .height = height};
  // Alternated, so that a shared machine's drift weighs on both forms alike; the first of each compiles.
  std::vector<double> ms[2];
  for (int i = 0; i <= repeats; ++i)
    for (PassForm form : {PassForm::fragment, PassForm::compute}) {
      const double t = finished_ms([&] { run_tonemap(shaders, vao, hdr, output, ToneMap{}, form); });
      if (i > 0) ms[int(form)].push_back(t);
    }
  glDeleteVertexArrays(1, &vao);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // The fastest of each: a shared machine's load only ever adds time, so the least is the form's own.
  probe.fragment_ms = *std::min_element(ms[0].begin(), ms[0].end());
  probe.compute_ms = *std::min_element(ms[1].begin(), ms[1].end());
  probe.chosen = probe.compute_ms <= 0.5 * probe.fragment_ms ? PassForm::compute : PassForm::fragment;
  return probe;
}

const PassFormProbe& device_pass_form(ShaderLibrary& shaders) {
  static std::map<std::string, PassFormProbe> measured;  // by GL renderer
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string renderer = r ? r : "";
  auto it = measured.find(renderer);
  if (it == measured.end()) it = measured.emplace(renderer, probe_pass_form(shaders, 512, 288, 7)).first;
  return it->second;
}

}  // namespace welkin

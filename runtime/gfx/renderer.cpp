#include "welkin/gfx/renderer.h"

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "welkin/core/error.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/tonemap_pass.h"

#ifndef WELKIN_SOURCE_SHADER_DIR
#error "WELKIN_SOURCE_SHADER_DIR must be defined by the build"
#endif

namespace welkin {

std::string runtime_shader_dir() {
  // Installed layout: <prefix>/lib/libwelkin_runtime.so and <prefix>/share/welkin/shaders.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&runtime_shader_dir), &info) && info.dli_fname) {
    auto installed =
        std::filesystem::path(info.dli_fname).parent_path().parent_path() / "share/welkin/shaders";
    std::error_code ec;
    if (std::filesystem::is_directory(installed, ec)) return installed.string();
  }
  return WELKIN_SOURCE_SHADER_DIR;
}

void RenderContext::draw_fullscreen_triangle() const {
  glBindVertexArray(empty_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

Renderer::Renderer(World& world) : world_(world), ctx_(world.resource<RenderContext>()) {
  if (!ctx_.empty_vao) {
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    ctx_.empty_vao = GlVertexArrayName(vao);
    ctx_.shaders.add_search_dir(runtime_shader_dir());
  }
  if (!ctx_.forms.measured) {
    ctx_.forms.device = device_pass_form(ctx_.shaders).chosen;
    ctx_.forms.measured = true;
  }
  // Reversed Z: depth 1 at the near plane, 0 at infinity, compared with GREATER.
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
}

namespace {

void check_frame_size(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error(ErrorInfo{.expected = "a frame size between 1x1 and 16384x16384",
                          .found = std::to_string(width) + "x" + std::to_string(height)});
}

}  // namespace

void Renderer::prepare_shaders() {
  // Every loaded module's shader folder, before the runtime's (also modules loaded after construction).
  for (const auto& name : world_.modules().loaded()) {
    const ModuleManifest* m = world_.modules().manifest(name);
    if (m && !m->data_dir.empty()) ctx_.shaders.add_search_dir(m->data_dir / "shaders", /*front=*/true);
  }
  // The composed material lighting of whatever terms the loaded modules declared.
  world_.resource<LightEnvironment>().install(ctx_.shaders);
}

FrameResult Renderer::update(const FrameInfo& frame) {
  FrameResult result;
  result.systems_run = world_.update(frame);
  prepare_shaders();
  return result;
}

FrameResult Renderer::render_view(const FrameInfo& frame, const FrameView& view) {
  const auto started = std::chrono::steady_clock::now();
  check_frame_size(view.width, view.height);
  FrameResult result = update(frame);
  ctx_.view = view;
  last_view_ = view;
  result.rendered_width = view.width, result.rendered_height = view.height;
  draw(frame, view.width, view.height, started, result);
  return result;
}

FrameResult Renderer::render_frame(const FrameInfo& frame, int width, int height, const Camera* view_camera) {
  const auto started = std::chrono::steady_clock::now();
  check_frame_size(width, height);
  FrameResult result = update(frame);

  Registry& reg = world_.registry();
  Entity cam = reg.first<Camera>();
  if (cam.is_null() && !view_camera)
    throw Error(ErrorInfo{.expected = "an entity with a core.Camera component",
                          .found = "none",
                          .message = "the scene has no camera"});
  const Camera& camera = view_camera ? *view_camera : *reg.get<Camera>(cam);
  // A moving view is rendered at the camera's moving_render_scale and upscaled; a still one whole, and
  // the systems then keep what they drew. Frames rendered alone are always whole.
  const FrameView whole = make_frame_view(camera, width, height);
  const bool moved = last_view_ && last_view_->width == width && last_view_->height == height &&
                     (last_view_->view_projection != whole.view_projection ||
                      last_view_->camera_position_m != whole.camera_position_m);
  last_view_ = whole;
  const float scale = moved && !frame.alone ? camera.moving_render_scale : 1.0f;
  const int rendered_width = std::clamp(int(std::lround(width * double(scale))), 1, width);
  const int rendered_height = std::clamp(int(std::lround(height * double(scale))), 1, height);
  ctx_.view = rendered_width == width && rendered_height == height
                  ? whole
                  : make_frame_view(camera, rendered_width, rendered_height);
  result.rendered_width = rendered_width, result.rendered_height = rendered_height;
  draw(frame, width, height, started, result);
  return result;
}

void Renderer::draw(const FrameInfo& frame, int width, int height,
                    std::chrono::steady_clock::time_point started, FrameResult& result) {
  const int rendered_width = ctx_.view.width, rendered_height = ctx_.view.height;
  const TextureFormat hdr_format = ctx_.radiance_format();
  if (!hdr_ || hdr_->desc().width != rendered_width || hdr_->desc().height != rendered_height ||
      hdr_->desc().format != hdr_format)
    hdr_ = std::make_unique<Texture>(
        TextureDesc{.width = rendered_width, .height = rendered_height, .format = hdr_format});
  if (!ldr_ || ldr_->desc().width != width || ldr_->desc().height != height)
    ldr_ = std::make_unique<Texture>(TextureDesc{
        .width = width, .height = height, .format = TextureFormat::rgba8, .linear_filter = false});

  RenderGraph graph;
  FrameTargets targets;
  targets.color = graph.import(std::string(kSceneColor.name), *hdr_);
  ResourceHandle output = graph.import("output", *ldr_);
  graph.add_pass("clear", [&](PassBuilder& b) {
    b.write(targets.color);
    targets.depth = b.create(std::string(kSceneDepth.name), TextureDesc{.width = rendered_width,
                                                        .height = rendered_height,
                                                        .format = TextureFormat::depth32f,
                                                        .linear_filter = false});
  }, [&, targets_copy = &targets](PassContext& pc) {
    Framebuffer fb(&pc.texture(targets_copy->color), &pc.texture(targets_copy->depth));
    fb.bind();
    glDepthMask(GL_TRUE);
    glClearColor(0, 0, 0, 1);
    glClearDepth(0.0);
    glClear(targets_copy->color_covered ? GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  });
  graph.publish(kSceneColor, targets.color);
  graph.publish(kSceneDepth, targets.depth);

  SystemContext sctx{.world = world_, .frame = frame, .graph = &graph, .targets = &targets,
                     .entering_system = [&graph](const std::string& name) { graph.set_system(name); }};
  auto rendered = world_.scheduler().run(Phase::render, sctx);
  graph.set_system("");
  result.systems_run.insert(result.systems_run.end(), rendered.begin(), rendered.end());
  result.geometry = targets.geometry;

  const FrameView& view = ctx_.view;
  const ToneMap tone_map{.tonemapper = int(view.tonemapper), .exposure = view.exposure};
  const PassForm tonemap_form = ctx_.forms.of("tonemap");
  graph.add_pass(
      "tonemap",
      [&](PassBuilder& b) {
        b.read(targets.color);
        b.write(output);
      },
      [&, this](PassContext& pc) {
        run_tonemap(ctx_.shaders, ctx_.empty_vao.id(), pc.texture(targets.color), pc.texture(output),
                    tone_map, tonemap_form);
      });
  graph.present(output);
  graph.compile();
  graph.execute(ctx_.backend);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("frame");
  result.timings = graph.timings();
  ctx_.last_timings = result.timings;
  result.culled_passes = graph.culled_passes();
  result.cpu_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count() -
      ctx_.backend.waited_ms();
}

ImageU8 Renderer::read_output() const { return read_texture_rgba8(*ldr_); }
ImageF Renderer::read_hdr() const { return read_texture_float(*hdr_); }

}  // namespace welkin

#pragma once
// Renders a world's frame: finds the camera, builds the frame graph (clear, the passes render
// systems add, tone mapping to an sRGB 8-bit target), runs it and keeps the per-pass timings.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "welkin/core/world.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_graph_backend.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/render_graph.h"
#include "welkin/gfx/screen_pass.h"
#include "welkin/gfx/shader.h"

namespace welkin {

// The frame's colour and depth as the renderer publishes them on the graph (FrameTargets holds the same).
inline constexpr GraphKey kSceneColor{"scene_color"};
inline constexpr GraphKey kSceneDepth{"scene_depth"};

struct FrameTargets {
  ResourceHandle color;  // RGBA16F linear radiance (scene-referred)
  ResourceHandle depth;  // depth32f, reversed Z (1 = near, 0 = infinity)
  // Set by a system whose first pass writes every pixel of `color` without reading it (a sky): the
  // frame's clear then clears only the depth (on llvmpipe the colour's clear is half of it).
  bool color_covered = false;
  // Every pixel where a pass may write `depth` (geometry), and a digest of what the geometry is
  // drawn from. A system whose pass writes the depth calls add_geometry when it records the pass,
  // with the pixels that pass may cover and a digest of its inputs (what it draws, where): the
  // full-screen passes over the geometry (aerial perspective) run inside the rectangle only, and
  // what reads the depth may be kept from an earlier frame while the digest holds.
  PixelRect geometry;
  uint64_t geometry_state = kFnv1aOffset;
  void add_geometry(const PixelRect& pixels, uint64_t state) {
    geometry.include(pixels);
    geometry_state = fnv1a_64_of(state, geometry_state);
  }
};

// GL state shared by every render system of a world (a world resource).
struct RenderContext {
  static constexpr std::string_view kTypeName = "core.RenderContext";
  ShaderLibrary shaders;
  GlGraphBackend backend;
  FrameView view;
  GlVertexArrayName empty_vao;  // full-screen triangles generate their vertices
  // Measurement (Renderer::set_full_precision): the frame's colour and the radiance that modules
  // keep between passes (sky tables, froxels) in 32-bit floats.
  bool full_precision = false;
  TextureFormat radiance_format() const {
    return full_precision ? TextureFormat::rgba32f : TextureFormat::rgba16f;
  }
  // The last frame's pass timings (what a system that keeps to a frame budget reads).
  std::vector<PassTiming> last_timings;
  // The form of each full-screen pass (fragment or compute), measured for the device at start-up.
  PassForms forms;
  void draw_fullscreen_triangle() const;
};

// The folder holding the runtime's shaders (installed tree, else the source tree).
std::string runtime_shader_dir();

struct FrameResult {
  std::vector<PassTiming> timings;
  std::vector<std::string> systems_run;
  std::vector<std::string> culled_passes;
  PixelRect geometry;  // FrameTargets::geometry as the frame's systems left it
  // Milliseconds the CPU spent on the frame (systems, graph, recording GL calls), without the time it
  // waited for the GPU to finish passes or report their timestamps.
  double cpu_ms = 0.0;
  // Smaller than the output while the view moves (Camera::moving_render_scale).
  int rendered_width = 0, rendered_height = 0;
};

class Renderer {
 public:
  // Requires a current GL 4.5 context.
  explicit Renderer(World& world);
  // Runs the world's update, pre-render and render systems and the frame graph. `view_camera`, when
  // given, replaces the scene's camera for this frame (the editor's fly camera) without touching it.
  FrameResult render_frame(const FrameInfo& frame, int width, int height,
                           const Camera* view_camera = nullptr);
  // The same frame seen through a view the caller made (a host program's matrices: welkin/host/sky.h),
  // at the view's size, always whole.
  FrameResult render_view(const FrameInfo& frame, const FrameView& view);
  // The last frame's tone-mapped output, and its linear HDR colour at the size it was rendered (smaller
  // than the output while the view moved: Camera::moving_render_scale).
  ImageU8 read_output() const;
  ImageF read_hdr() const;
  const Texture& output_texture() const { return *ldr_; }
  const Texture& hdr_texture() const { return *hdr_; }
  RenderContext& context() { return ctx_; }
  // The loaded modules' shader folders and the composed lighting installed in the shader library
  // (every frame does it; a host compiling materials before its first frame calls it).
  void prepare_shaders();
  // The HDR colour, and what modules keep of radiance between passes, in 32-bit floats instead of 16
  // (measurement: a twilight sky's radiance per lux of sun sits in half floats' subnormal range,
  // where their steps are 6e-8). From the next frame on.
  void set_full_precision(bool full) { ctx_.full_precision = full; }

 private:
  // The update and pre-render systems, the modules' shader folders and the composed lighting.
  FrameResult update(const FrameInfo& frame);
  // The frame graph over ctx_.view (whose size is the rendered size) into a `width` x `height` output.
  void draw(const FrameInfo& frame, int width, int height, std::chrono::steady_clock::time_point started,
            FrameResult& result);

  World& world_;
  RenderContext& ctx_;
  std::unique_ptr<Texture> hdr_, ldr_;
  std::optional<FrameView> last_view_;  // the last frame's whole view, to tell a moving view
};

}  // namespace welkin

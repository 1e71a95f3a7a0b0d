#pragma once
// Welkin inside a host program: the host keeps its window, GL context, camera, geometry, shaders and
// framebuffer; each frame it hands Welkin its view, projection, colour and depth, and Welkin adds the
// sky, clouds, god rays, haze and aerial perspective over the host's geometry. docs/embedding.md
// shows the smallest complete program.
//
// Conventions
// - World frame: Welkin's scene frame, x east, y north, z up, metres (double precision).
// - The host's colour is linear radiance in Welkin's units (the lights' lux through a material's
//   BRDF: what material_glsl()'s shade_lambert and shade_pbr return), in a float texture.
// - Depth: forward (OpenGL's default clip control, near 0, far 1, cleared to 1) or reversed
//   (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), near 1, far or infinity 0, cleared to 0); any
//   symmetric perspective projection, finite or infinite far plane. A pixel at the far plane's depth
//   holds no geometry: Welkin draws the sky there.
// - GL state: Sky's calls leave the host's state as they found it (welkin/host/gl_state.h lists
//   what is saved and restored), except bind_material_lighting, which binds on purpose.
#include <epoxy/gl.h>

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>

#include "welkin/gfx/renderer.h"

namespace welkin {
class World;
}

namespace welkin::host {

enum class DepthConvention {
  forward,   // glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE) (GL's default): near 0, far 1
  reversed,  // glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): near 1, far (or infinity) 0
};

// The host's render targets: GL_TEXTURE_2D names of one size (not multisampled).
struct Targets {
  GLuint color = 0;   // RGBA16F or RGBA32F linear radiance; receives the composed frame (linear HDR)
  GLuint depth = 0;   // the depth texture the host drew `color` with (any depth or depth-stencil format)
  GLuint output = 0;  // optional RGBA8 or SRGB8_ALPHA8: receives the exposed, tone-mapped, sRGB-encoded frame
  int width = 0, height = 0;
};

struct View {
  glm::dmat4 view{1.0};  // world to the host's eye space (rigid: rotation and translation; looks down -z)
  glm::mat4 projection{1.0f};  // the host's perspective projection (symmetric)
  DepthConvention depth = DepthConvention::reversed;
};

struct Frame {
  View view;
  Targets targets;
  double time_s = 0.0;  // since the host started: clocks, wind and animation advance with dt_s
  double dt_s = 0.0;
  uint64_t index = 0;
};

class Sky {
 public:
  // Requires a current OpenGL 4.5 core context and a world whose scene is loaded (load_scene_file);
  // the world outlives the Sky. Exposure and tone mapping come from the scene's core.Camera when
  // it has one (its position and orientation are the host's), else the camera's defaults.
  explicit Sky(World& world);
  ~Sky();
  Sky(const Sky&) = delete;
  Sky& operator=(const Sky&) = delete;

  // Composes the frame over the host's targets. Throws welkin::Error naming the bad input (a target
  // that is not a 2D texture of the size and kind above, a projection that is not perspective).
  // `draw_geometry`, when given, draws the host's geometry into its targets: Welkin calls it once,
  // in the middle of the frame, once this frame's lights are computed (the sky's tables, the
  // shadows) and bound as bind_material_lighting binds them, with the host's GL state as it was
  // when render was called. So the host's materials are lit by this frame's sun and sky, the first
  // frame included. Without it the targets hold what the host drew before the call.
  FrameResult render(const Frame& frame, const std::function<void()>& draw_geometry = {});

  // Sets a scene field by its component's name and path, e.g. the time of day:
  // set("timeofday.TimeOfDay", "local_time_h", 17.5). Throws Error naming the path.
  void set(std::string_view component, std::string_view path, const nlohmann::json& value);
  nlohmann::json get(std::string_view component, std::string_view path);

  // GLSL for the host's materials, lit as Welkin lights its own: a header to compile before the
  // host's fragment code (it starts with #version 450 core and defines shade_lambert(albedo,
  // normal, camera_relative_position) and shade_pbr(...) in welkin/shading.glsl). The lighting is
  // the scene's (sun, moon, sky, shadows of the modules loaded); positions are world minus camera.
  // Recompile when lighting_version() changes (a module or a term was added).
  std::string material_glsl();
  // The host's vertex shader and its fragment code after material_glsl(), compiled and linked: a
  // program the host owns. Throws Error naming the host's code, with the compiler's log (the
  // fragment code's lines counted from its own first line).
  Program material_program(std::string_view vertex, std::string_view fragment);
  uint64_t lighting_version() const;
  // Binds what material_glsl's functions read (texture units from 8 and uniform blocks from 4 up;
  // units 0..7 and blocks 0..3 stay the host's). render's draw_geometry is called with them bound;
  // outside it they reflect the last rendered frame's lights (none before the first frame).
  void bind_material_lighting();

  World& world() { return world_; }
  Renderer& renderer() { return *renderer_; }

 private:
  void copy(const Texture& from, GLuint to, int width, int height);

  World& world_;
  std::unique_ptr<Renderer> renderer_;
  GLuint copy_framebuffers_[2] = {0, 0};
  GLuint sampler_ = 0;
  uint64_t serial_ = 0;
};

// Welkin's view of a host's matrices: position and basis from `view`, field of view and near
// plane from `projection`; exposure and tone mapping from `camera`. Throws Error when `view` is
// not rigid or `projection` not a symmetric perspective of the targets' aspect.
FrameView frame_view_of(const View& view, int width, int height, const Camera& camera);
// The host projection's terms that turn its depth back into distance along the view axis:
// distance = b / (ndc_z + a), with ndc_z = 2 depth - 1 (forward) or depth (reversed).
glm::vec2 depth_terms(const glm::mat4& projection);

}  // namespace welkin::host

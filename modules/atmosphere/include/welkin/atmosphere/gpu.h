#pragma once
// The atmosphere's GPU side: the uniform block every atmosphere shader and material sees, the LUTs
// a world keeps between frames, and the render system that fills them through the frame graph.
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <string_view>

#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/gpu_blocks.h"
#include "welkin/atmosphere/stars.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_objects.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::atmosphere {

// The block for one frame. Sun and moon may be null (a default sun; no moon). Pure CPU.
FrameBlock make_uniforms(const Atmosphere& atmosphere, const Sun* sun, const Moon* moon,
                         const FrameView& view);
// The persistent LUTs' sizes and step counts: with the medium, what they are made from.
inline std::array<int, 6> persistent_lut_sizes(const FrameBlock& u) {
  return {u.transmittance_width,  u.transmittance_height,  u.transmittance_steps,
          u.multiscattering_size, u.multiscattering_steps, u.multiscattering_iterations};
}
// True when two frames' uniforms need different transmittance/multi-scattering LUTs: their media or
// the LUTs' sizes differ.
bool luts_differ(const FrameBlock& a, const FrameBlock& b);
// True when they need a different sky-view LUT: everything but the view's orientation and the
// aerial-perspective volume's settings (the LUT is laid out around the camera's position and the sun).
bool sky_view_differs(const FrameBlock& a, const FrameBlock& b);
// True when they need a different aerial-perspective volume: anything but the view itself differs
// (the volume's frustum is its own, aerial_view_projection).
bool aerial_perspective_differs(const FrameBlock& a, const FrameBlock& b);

// A turning view (the camera in place, only its orientation changing) keeps its aerial-perspective
// volume while the view stays inside the volume's frustum; the volume it makes then is wider than
// the view by this factor on the image plane (about 6 degrees a side at a 60 degree field), so that
// a turn of a degree a frame remakes it one frame in six. A still or moving camera gets a volume
// fitted to its view.
inline constexpr float kAerialTurningMargin = 1.25f;
// Sets u's aerial frustum: the kept volume's when it serves this view, a wider one when the view goes
// on turning out of it, the view's own otherwise (a single turn, then still, makes one fitted volume,
// so that what reads the volume, the clouds' kept march, starts over once). `kept` is what the volume
// was last made from (when `kept_valid`), `previous_view_projection` the last frame's view, and
// `turned_before` whether that frame's view had turned from the one before it.
void choose_aerial_frustum(FrameBlock& u, const FrameBlock& kept, bool kept_valid,
                           const glm::mat4& previous_view_projection, bool turned_before);

// Layers of the multi-scattering LUT, side by side (multiscattering_lut.comp, common.glsl): the mean
// light arriving at a point, its dipole and quadrupole in the point's frame (z up, y towards the
// sun's azimuth) in the next three, and the ground's sky light.
inline constexpr int kMultiscatteringLayers = 5;

// LUTs and the uniform buffer of one world (a world resource, so GL objects live with the world).
struct AtmosphereGpu {
  static constexpr std::string_view kTypeName = "atmosphere.Gpu";
  std::unique_ptr<Texture> transmittance, multiscattering, sky_view, aerial_inscattering,
      aerial_transmittance, sky_irradiance;
  std::unique_ptr<Texture> multiscattering_scratch;  // the other half of the LUT's iteration
  std::unique_ptr<Buffer> stars;                     // the star catalogue (stars.h), when drawn
  Stars stars_built_from;                            // what `stars` was made from
  std::unique_ptr<Buffer> uniform_buffer;
  FrameBlock uniforms{};      // as last uploaded
  FrameBlock lut_uniforms{};  // what the persistent LUTs were built from
  bool luts_valid = false;
  int lut_builds = 0;       // transmittance + multi-scattering regenerations (tests, stats)
  int lut_cache_reads = 0;  // the same, read from the disk cache instead
  // The per-frame LUTs are kept while nothing they depend on changed (a still camera, a still sun):
  // reusing them is exact, not an approximation.
  FrameBlock sky_view_uniforms{}, aerial_uniforms{};
  bool view_turned = false;  // the last frame's view differed from the one before (choose_aerial_frustum)
  bool sky_view_valid = false, aerial_valid = false;
  int sky_view_builds = 0, aerial_builds = 0;
  // The next frame remakes the per-frame LUTs as if the view and the sun had moved: what a benchmark
  // of the atmosphere's per-frame cost times (a still camera would otherwise reuse them).
  void forget_per_frame_luts() {
    sky_view_valid = aerial_valid = false;
    kept_sky_inputs.clear();
    drawn_sky_inputs.clear();
  }
  // The sky as the sky pass drew it (sky, discs), copied into the frame while everything it was
  // drawn from is the same (background_system): a still view does not draw it again. It is kept
  // from the second frame in a row drawn from the same inputs, so a moving view pays no copy.
  std::unique_ptr<Texture> kept_sky;
  std::string kept_sky_inputs, drawn_sky_inputs;
  int sky_draws = 0;
  // Where the light environment put the block and the LUTs (add_light_term fills them).
  struct Bindings {
    GLuint block = 0, transmittance = 0, multiscattering = 0, sky_view = 0, aerial_inscattering = 0,
           aerial_transmittance = 0, sky_irradiance = 0;
  } bindings;
};

// Declares the atmosphere's light term (sun, moon and sky through the LUTs; aerial perspective) in
// the world's light environment and records the bindings it was given.
void add_light_term(World& world);

// Binds the uniform block and every LUT at the light environment's units (materials get this
// through LightEnvironment::bind; the atmosphere's own passes and tools call it directly).
void bind_for_materials(const AtmosphereGpu& gpu);

// Stage::tables, before geometry: transmittance and multi-scattering LUTs when the
// medium changed, the sky-view LUT, the aerial-perspective volume, sky irradiance.
void lut_system(SystemContext& sc);
// Stage::background, before geometry and after the light environment's inputs: the sky, its
// discs and stars over the whole target (the geometry drawn after covers them).
void background_system(SystemContext& sc);
// Stage::aerial_perspective, after geometry: aerial perspective over the depth buffer.
void sky_system(SystemContext& sc);

}  // namespace welkin::atmosphere

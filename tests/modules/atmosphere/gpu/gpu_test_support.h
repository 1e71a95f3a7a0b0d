#pragma once
// Shared by the atmosphere GPU tests: one headless GL 4.5 context per test binary, worlds with the
// atmosphere module linked statically, small renders, LUT readback and checks of whole images.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/gpu.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

#if WELKIN_HAVE_ATMOSPHERE_REFERENCE
#include "reference/atmosphere_model.h"
#include "validation/reference_model.h"
#endif

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
}

namespace welkin::atmosphere::test {

// One context for the whole binary: creating EGL contexts per test is slow on llvmpipe.
inline GlContext& gl_context() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

// A scene with a camera and the given atmosphere components (JSON objects of their fields).
inline nlohmann::json scene(const nlohmann::json& camera, const nlohmann::json& atmosphere,
                            const nlohmann::json& sun = nlohmann::json::object(),
                            const nlohmann::json* moon = nullptr) {
  nlohmann::json components = {
      {"core.Camera", camera}, {"atmosphere.Atmosphere", atmosphere}, {"atmosphere.Sun", sun}};
  if (moon) components["atmosphere.Moon"] = *moon;
  return {{"welkin_scene", 1},
          {"entities", nlohmann::json::array({{{"name", "all"}, {"components", components}}})}};
}

// A world that has loaded `doc` and rendered `frames` frames of width x height.
struct Rendered {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
  FrameResult last;
  AtmosphereGpu& gpu() { return world->resource<AtmosphereGpu>(); }
  void frame(int width, int height, uint64_t index = 0) {
    last = renderer->render_frame(FrameInfo{.index = index}, width, height);
  }
};

inline Rendered render(const nlohmann::json& doc, int width = 32, int height = 18, int frames = 1) {
  gl_context().make_current();
  Rendered r;
  r.world = std::make_unique<World>();
  r.world->modules().add_static(welkin::modules::atmosphere_module());
  load_scene(*r.world, doc, "test scene");
  r.renderer = std::make_unique<Renderer>(*r.world);
  for (int i = 0; i < frames; ++i) r.frame(width, height, uint64_t(i));
  return r;
}

struct ImageStats {
  bool finite = true;
  float min = INFINITY, max = -INFINITY;
};

inline ImageStats stats(const ImageF& image) {
  ImageStats s;
  for (size_t i = 0; i < image.rgba.size(); ++i) {
    if (i % 4 == 3) continue;  // alpha carries no radiometry
    float v = image.rgba[i];
    if (!std::isfinite(v))
      s.finite = false;
    else
      s.min = std::min(s.min, v), s.max = std::max(s.max, v);
  }
  return s;
}

// Every slice of a texture (3D textures are read layer by layer).
inline ImageStats stats(const Texture& t) {
  ImageStats all;
  for (int layer = 0; layer < t.desc().depth; ++layer) {
    ImageStats s = stats(read_texture_float(t, layer));
    all.finite = all.finite && s.finite;
    all.min = std::min(all.min, s.min);
    all.max = std::max(all.max, s.max);
  }
  return all;
}

}  // namespace welkin::atmosphere::test

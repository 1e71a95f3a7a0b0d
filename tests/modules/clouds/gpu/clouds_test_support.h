#pragma once
// Shared by the clouds GPU tests: one headless GL context per binary, worlds with the clouds (and
// atmosphere) modules linked statically, small renders and whole-image checks.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "welkin/clouds/components.h"
#include "clouds_gpu.h"  // the module's private GPU state (modules/clouds/src)
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& clouds_module();
const ModuleDefinition& atmosphere_module();
}  // namespace welkin::modules

namespace welkin::clouds::test {

inline GlContext& gl_context() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

// A camera, a sun and whatever components are given, on one entity each.
inline nlohmann::json scene(const nlohmann::json& components) {
  nlohmann::json entities = nlohmann::json::array();
  for (auto& [name, value] : components.items()) entities.push_back({{"name", name}, {"components", {{name, value}}}});
  return {{"welkin_scene", 1}, {"entities", entities}};
}

// The scene's entity holding `component` (scene() gives each its own).
inline nlohmann::json& entity_with(nlohmann::json& doc, const std::string& component) {
  for (nlohmann::json& e : doc["entities"])
    if (e["components"].contains(component)) return e;
  throw Error("test scene without " + component);
}
inline void remove_entity_with(nlohmann::json& doc, const std::string& component) {
  nlohmann::json& entities = doc["entities"];
  for (size_t i = 0; i < entities.size(); ++i)
    if (entities[i]["components"].contains(component)) return entities.erase(i);
}

struct Rendered {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
  FrameResult last;
  uint64_t frame_index = 0;
  void frame(int width, int height) { last = renderer->render_frame(FrameInfo{.index = frame_index++}, width, height); }
  VolumetricClouds& clouds() { return *world->registry().get<VolumetricClouds>(world->registry().first<VolumetricClouds>()); }
  Camera& camera() { return *world->registry().get<Camera>(world->registry().first<Camera>()); }
  bool ran(const std::string& pass) const {
    for (const auto& t : last.timings)
      if (t.name == pass) return true;
    return false;
  }
};

inline Rendered render(const nlohmann::json& doc, int width = 32, int height = 18) {
  gl_context().make_current();
  Rendered r;
  r.world = std::make_unique<World>();
  r.world->modules().add_static(welkin::modules::atmosphere_module());
  r.world->modules().add_static(welkin::modules::clouds_module());
  load_scene(*r.world, doc, "test scene");
  r.renderer = std::make_unique<Renderer>(*r.world);
  r.frame(width, height);
  return r;
}

struct ImageStats {
  bool finite = true;
  float min = INFINITY, max = -INFINITY;
  double mean = 0.0;
};

inline ImageStats stats(const ImageF& image) {
  ImageStats s;
  size_t n = 0;
  for (size_t i = 0; i < image.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const float v = image.rgba[i];
    if (!std::isfinite(v)) {
      s.finite = false;
      continue;
    }
    s.min = std::min(s.min, v), s.max = std::max(s.max, v);
    s.mean += v, ++n;
  }
  s.mean /= double(std::max<size_t>(n, 1));
  return s;
}

// A stiff case: `doc` with its camera at `camera`, rendered small; its frame must stay finite and
// non-negative.
inline Rendered render_stiff_case(nlohmann::json doc, const glm::dvec3& camera, const std::string& name) {
  entity_with(doc, "core.Camera")["components"]["core.Camera"]["position_m"] = {camera.x, camera.y, camera.z};
  Rendered r = render(doc, 48, 27);
  const ImageStats s = stats(r.renderer->read_hdr());
  EXPECT_TRUE(s.finite) << name;
  EXPECT_GE(s.min, 0.0f) << name;
  return r;
}

// Noon, the sun 40 degrees up, a camera on the ground looking 10 degrees up, default clouds.
inline nlohmann::json noon(const nlohmann::json& clouds = nlohmann::json::object()) {
  return scene({{"core.Camera", {{"position_m", {0, 0, 100}}, {"heading_deg", 210}, {"pitch_deg", 10}, {"ev100", 14}}},
                {"atmosphere.Atmosphere", nlohmann::json::object()},
                {"atmosphere.Sun", {{"azimuth_deg", 240}, {"elevation_deg", 40}}},
                {"clouds.VolumetricClouds", clouds}});
}

}  // namespace welkin::clouds::test

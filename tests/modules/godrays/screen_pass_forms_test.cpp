// God rays' shafts and application, and the atmosphere's ground light (which needs a module that
// shadows surfaces: the clouds), in their compute form against their fragment form
// (welkin/gfx/screen_pass.h), on llvmpipe, at 67x43: a size no work group of 8 x 8 divides.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pass_forms.h"
#include "welkin/core/module.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/screen_pass.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& clouds_module();
const ModuleDefinition& godrays_module();
const ModuleDefinition& terrain_module();
const ModuleDefinition& timeofday_module();
}  // namespace welkin::modules

namespace welkin::godrays {
namespace {

using nlohmann::json;
using testing::FormFrame;

GlContext& gl() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

constexpr int kW = 67, kH = 43;

std::function<std::unique_ptr<World>()> world_of(const json& doc) {
  return [doc] {
    gl().make_current();
    auto world = std::make_unique<World>();
    for (const auto* m :
         {&modules::atmosphere_module(), &modules::clouds_module(), &modules::godrays_module(),
          &modules::terrain_module(), &modules::timeofday_module()})
      world->modules().add_static(*m);
    load_scene(*world, doc, "test scene");
    return world;
  };
}

// assets/scenes/godrays-sunset.json (terrain, clouds, the sun low ahead), its god rays replaced by
// `rays` (none when null) and `extra` components added.
json sunset(const json& rays, const json& extra = json::object()) {
  std::ifstream in(std::filesystem::path(WELKIN_SOURCE_DIR) / "assets/scenes/godrays-sunset.json");
  json doc = json::parse(in);
  json kept = json::array();
  for (auto& e : doc["entities"]) {
    if (e["components"].contains("godrays.GodRays")) {
      if (rays.is_null()) continue;
      e["components"]["godrays.GodRays"] = rays;
    }
    kept.push_back(e);
  }
  if (!extra.empty()) kept.push_back({{"name", "extra"}, {"components", extra}});
  doc["entities"] = kept;
  return doc;
}

// Both forms of `pass`: the frames agree within `relative` of each channel above 1e-4 of the frame's
// brightest (rounding to half floats, and the order of a sum), and their outputs within one level.
void expect_forms_agree(const json& doc, const std::string& pass, double relative) {
  const FormFrame f = testing::render_with_form(world_of(doc), pass, PassForm::fragment, kW, kH);
  const FormFrame c = testing::render_with_form(world_of(doc), pass, PassForm::compute, kW, kH);
  ASSERT_TRUE(f.ran(pass) && c.ran(pass)) << pass;
  const testing::HdrDifference d = testing::hdr_difference(f.hdr, c.hdr, 1e-4);
  EXPECT_GT(d.brightest, 0.0);
  EXPECT_LE(d.worst, relative) << pass << " at pixel " << d.x << "," << d.y;
  EXPECT_LE(testing::output_difference(f.output, c.output), 1) << pass;
}

TEST(ScreenPassForms, MarchedShafts) {
  const json rays = {{"method", "marched"}, {"jitter", false}};
  expect_forms_agree(sunset(rays), "godrays.shafts", 2e-3);
}

TEST(ScreenPassForms, MarchedShaftsJitteredAndFiltered) {
  expect_forms_agree(sunset({{"method", "marched"}}), "godrays.shafts", 2e-3);
}

TEST(ScreenPassForms, ScreenSpaceShafts) {
  expect_forms_agree(sunset({{"method", "screen_space"}}), "godrays.shafts", 2e-3);
}

TEST(ScreenPassForms, ShaftsApplied) {
  expect_forms_agree(sunset({{"method", "screen_space"}}), "godrays.apply", 2e-3);
  expect_forms_agree(sunset({{"method", "marched"}}), "godrays.apply", 2e-3);
}

TEST(ScreenPassForms, HazeAndShaftsApplied) {
  expect_forms_agree(sunset({{"method", "marched"}}, {{"godrays.Haze", json::object()}}), "godrays.apply",
                     2e-3);
  expect_forms_agree(sunset(nullptr, {{"godrays.Haze", json::object()}}), "godrays.apply", 2e-3);
}

// The planet's ground under a deck of stratus (its shadow on the ground is the light environment's),
// seen past no geometry: the ground light runs on the lower rows.
TEST(ScreenPassForms, GroundLightUnderCloudShadows) {
  const json deck = {{"weather_system_amount", 0.0},
                     {"layers",
                      {{{"genus", "stratus"},
                        {"base_altitude_m", 1000},
                        {"thickness_m", 2000},
                        {"coverage", 0.6},
                        {"density_per_m", 0.1}}}}};
  const json components = {{"core.Camera",
                            {{"position_m", {0, 0, 300}},
                             {"heading_deg", 30},
                             {"pitch_deg", -3},
                             {"vertical_fov_deg", 20},
                             {"ev100", 14}}},
                           {"atmosphere.Atmosphere", json::object()},
                           {"atmosphere.Sun", {{"azimuth_deg", 10}, {"elevation_deg", 55}}},
                           {"clouds.VolumetricClouds", deck}};
  json entities = json::array();
  for (auto& [name, value] : components.items())
    entities.push_back({{"name", name}, {"components", {{name, value}}}});
  expect_forms_agree({{"welkin_scene", 1}, {"entities", entities}}, "atmosphere.ground_light", 2e-3);
}

}  // namespace
}  // namespace welkin::godrays

// The god rays against an exact case (air under an opaque cloud deck, whose shafts are the whole
// single-scattered sunlight of the air, from the atmosphere's double-precision quadrature), a scene
// with nothing casting shadows (no light taken), convergence with steps, and the stiff cases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <tuple>

#include "frame_block.h"
#include "golden.h"
#include "gpu_block_readback.h"
#include "reference/single_scattering.h"
#include "shafts.h"
#include "validation/reference_model.h"
#include "welkin/atmosphere/components.h"
#include "welkin/core/files.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/godrays/components.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& clouds_module();
const ModuleDefinition& godrays_module();
}  // namespace welkin::modules

namespace welkin::godrays {
namespace {

namespace ref = welkin::atmosphere::reference;
using nlohmann::json;

GlContext& gl_context() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

json scene(const json& components) {
  json entities = json::array();
  for (auto& [name, value] : components.items()) entities.push_back({{"name", name}, {"components", {{name, value}}}});
  return {{"welkin_scene", 1}, {"entities", entities}};
}

// A deck of stratus 1-3 km up, uniform and opaque (optical depth > 60 along the sun's path): the air
// below it is in shadow (as far as the clouds' shadow map resolves it: its nearer cascades).
json opaque_deck() {
  return {{"weather_system_amount", 0.0},
          {"layers", {{{"genus", "stratus"}, {"base_altitude_m", 1000}, {"thickness_m", 2000}, {"coverage", 1.0},
                       {"density_per_m", 0.1}, {"shape_amount", 0.0}, {"detail_amount", 0.0}, {"base_variation_m", 0.0}}}}};
}

// Camera 300 m up looking 3 degrees down with a 10-degree field: the lower rows see the ground
// within 9 km, under the deck and inside its shadow map.
json looking_down(const json& extra, const json& sun = {{"azimuth_deg", 10}, {"elevation_deg", 55}}) {
  json c = {{"core.Camera", {{"position_m", {0, 0, 300}}, {"heading_deg", 30}, {"pitch_deg", -3}, {"vertical_fov_deg", 10}, {"ev100", 14}}},
            {"atmosphere.Atmosphere", json::object()},
            {"atmosphere.Sun", sun}};
  for (auto& [k, v] : extra.items()) c[k] = v;
  return scene(c);
}

struct Render {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
  FrameResult last;
  bool ran(const std::string& pass) const {
    for (const auto& t : last.timings)
      if (t.name == pass) return true;
    return false;
  }
};

Render render(const json& doc, int width, int height) {
  gl_context().make_current();
  Render r;
  r.world = std::make_unique<World>();
  r.world->modules().add_static(modules::atmosphere_module());
  r.world->modules().add_static(modules::clouds_module());
  r.world->modules().add_static(modules::godrays_module());
  load_scene(*r.world, doc, "test scene");
  r.renderer = std::make_unique<Renderer>(*r.world);
  r.renderer->set_full_precision(true);  // the shafts are differences of two frames
  r.last = r.renderer->render_frame(FrameInfo{.index = 3, .alone = true}, width, height);
  return r;
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

constexpr int kW = 24, kH = 24;

// Largest relative error, over the rows that see the ground within the shafts' reach, of the light the
// marched shafts take away against the quadrature's single scattering of the same air.
double exact_case_error(int steps) {
  const json shafts = {{"method", "marched"}, {"resolution_divisor", 1}, {"steps", steps}, {"jitter", false}, {"max_distance_m", 4500}};
  Render without = render(looking_down({{"clouds.VolumetricClouds", opaque_deck()}}), kW, kH);
  Render with = render(looking_down({{"clouds.VolumetricClouds", opaque_deck()}, {"godrays.GodRays", shafts}}), kW, kH);
  EXPECT_TRUE(with.ran("godrays.shafts"));
  const ImageF a = without.renderer->read_hdr(), b = with.renderer->read_hdr();
  World& w = *with.world;
  const auto& atm = *w.registry().get<atmosphere::Atmosphere>(w.registry().first<atmosphere::Atmosphere>());
  const ref::AtmosphereModel model = atmosphere::to_reference(atm);
  const auto& sun_light = *w.registry().get<atmosphere::Sun>(w.registry().first<atmosphere::Sun>());
  const glm::vec3 e_sun = sun_light.color * sun_light.illuminance_lux * sun_light.visible_fraction;
  const glm::dvec3 sun = glm::dvec3(*scene_sun_direction(w));
  const FrameView& view = w.resource<RenderContext>().view;
  const glm::dvec3 camera_km(0.0, 0.0, model.bottom_radius_km + 0.3);
  double worst = 0.0;
  int rows = 0;
  for (int y = 0; y < kH; ++y) {
    const glm::dvec3 probe = glm::dvec3(pixel_direction(view, kW / 2 + 0.5, y + 0.5));
    // The ground within 4 km: beyond, the clouds' shadow map (its second cascade, 40 steps over 15 km
    // per column) lets part of the sun through a 2 km deck, which is the clouds' error, not the shafts'.
    if (probe.z > -0.075) continue;
    ++rows;
    for (int x = 0; x < kW; x += 5) {
      const glm::dvec3 dir = glm::normalize(glm::dvec3(pixel_direction(view, x + 0.5, y + 0.5)));
      ref::SingleScatteringSettings settings;
      settings.max_distance_km = 4.5;
      const glm::dvec3 l = ref::single_scattering(model, camera_km, dir, sun, settings).radiance * glm::dvec3(e_sun);
      const double expected = 0.2126 * l.x + 0.7152 * l.y + 0.0722 * l.z;
      // Images run top to bottom in rows: read_hdr's row 0 is the top.
      const double taken = luminance(a.pixel(x, y)) - luminance(b.pixel(x, y));
      EXPECT_GT(expected, 0.0);
      worst = std::max(worst, std::abs(taken - expected) / expected);
    }
  }
  EXPECT_GE(rows, 6);
  return worst;
}

TEST(GodRays, UnderAnOpaqueDeckTheShaftsAreTheAirsWholeSingleScattering) {
  // Each step integrates its own exponential exactly: even one step is within 0.1% here (the air
  // changes little over 4 km); what remains is the transmittance LUT's and float's error.
  EXPECT_LT(exact_case_error(1), 0.005);
  EXPECT_LT(exact_case_error(32), 0.005);
}

// Under broken cloud the shadow along a ray comes and goes: there the steps matter, and the marched
// shafts must approach the converged march (512 steps) as they grow.
TEST(GodRays, UnderBrokenCloudTheShaftsConvergeWithSteps) {
  json broken = opaque_deck();
  broken["layers"][0]["coverage"] = 0.5;
  broken["layers"][0]["shape_amount"] = 1.0;
  auto shafts_image = [&](int steps) {
    const json shafts = {{"method", "marched"}, {"resolution_divisor", 1}, {"steps", steps}, {"jitter", false}, {"max_distance_m", 20000}};
    const json sun = {{"azimuth_deg", 30}, {"elevation_deg", 25}};
    Render r = render(looking_down({{"clouds.VolumetricClouds", broken}, {"godrays.GodRays", shafts}}, sun), kW, kH);
    return r.renderer->read_hdr();
  };
  const ImageF reference = shafts_image(512);
  auto error = [&](int steps) {
    const ImageF img = shafts_image(steps);
    double e = 0.0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) e += std::abs(luminance(&img.rgba[i]) - luminance(&reference.rgba[i]));
    return e;
  };
  const double e2 = error(2), e8 = error(8), e64 = error(64);
  EXPECT_GT(e2, 0.0) << "two steps must miss some of the shadow";
  EXPECT_LT(e8, e2);
  EXPECT_LT(e64, e8);
}

TEST(GodRays, NothingCastingShadowsTakesNoLight) {
  Render without = render(looking_down({}), kW, kH);
  Render with = render(looking_down({{"godrays.GodRays", {{"steps", 8}}}}), kW, kH);
  ASSERT_TRUE(with.ran("godrays.shafts"));
  EXPECT_EQ(without.renderer->read_hdr().rgba, with.renderer->read_hdr().rgba);
}

TEST(GodRays, SunOnScreenOnlyWhereItsImageIs) {
  const glm::mat4 vp = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 100.0f);  // looking down -z
  EXPECT_FALSE(sun_on_screen(vp, {0, 0, 1}).has_value()) << "behind the camera";
  const auto centre = sun_on_screen(vp, {0, 0, -1});
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR(centre->x, 0.5f, 1e-6f);
  const auto edge = sun_on_screen(vp, glm::normalize(glm::vec3(1, 0, -1)));  // exactly on the right edge
  ASSERT_TRUE(edge.has_value());
  EXPECT_NEAR(edge->x, 1.0f, 1e-5f);
  EXPECT_FALSE(sun_on_screen(vp, glm::normalize(glm::vec3(1.01f, 0, -1))).has_value()) << "just off the edge";
  EXPECT_FALSE(sun_on_screen(vp, {1, 0, 0}).has_value()) << "in the image plane (w = 0)";
}

TEST(GodRays, StiffCasesStayFiniteNonNegativeAndBounded) {
  auto check = [](const json& sun, const json& shafts, bool runs, bool deck = false) {
    const json clouds = deck ? json{{"clouds.VolumetricClouds", opaque_deck()}} : json::object();
    json with_shafts = clouds;
    with_shafts["godrays.GodRays"] = shafts;
    Render base = render(looking_down(clouds, sun), 16, 16);
    Render r = render(looking_down(with_shafts, sun), 16, 16);
    EXPECT_EQ(r.ran("godrays.shafts"), runs) << sun.dump() << shafts.dump();
    const ImageF a = base.renderer->read_hdr(), b = r.renderer->read_hdr();
    for (size_t i = 0; i < b.rgba.size(); ++i) {
      ASSERT_TRUE(std::isfinite(b.rgba[i])) << sun.dump() << shafts.dump();
      // Never more light than without shafts, never below zero (beyond float rounding of the subtraction).
      ASSERT_LE(b.rgba[i], a.rgba[i] * (1.0f + 1e-5f) + 1e-6f) << sun.dump() << shafts.dump();
      ASSERT_GE(b.rgba[i], -1e-3f * std::abs(a.rgba[i]) - 1e-6f) << sun.dump() << shafts.dump();
    }
  };
  const json overhead = {{"azimuth_deg", 0}, {"elevation_deg", 90}};
  check(overhead, {{"steps", 1}}, true, true);
  check(overhead, {{"steps", kMaxStepsPerRay}, {"resolution_divisor", 8}}, true, true);
  check(overhead, {{"max_distance_m", 1e6}}, true);
  check({{"azimuth_deg", 30}, {"elevation_deg", 0}}, {{"steps", 8}}, true);   // on the horizon, in front
  check({{"azimuth_deg", 30}, {"elevation_deg", -30}}, {{"steps", 8}}, false);  // no sunlit air within reach
  check({{"azimuth_deg", 210}, {"elevation_deg", 5}}, {{"method", "screen_space"}}, false);  // behind the camera
  check({{"azimuth_deg", 30}, {"elevation_deg", 1}}, {{"method", "screen_space"}, {"screen_samples", 1}}, true);
  // On the screen but below the camera's horizon (its dip at 300 m is 0.56 degrees): no sun image.
  check({{"azimuth_deg", 30}, {"elevation_deg", -1}}, {{"method", "screen_space"}}, false);
}

}  // namespace
}  // namespace welkin::godrays

namespace welkin::godrays {
namespace {

// Every preset is a valid godrays.GodRays whose method is the one its name says.
TEST(GodRaysPresets, EveryPresetFileLoads) {
  gl_context().make_current();
  World world;
  world.modules().add_static(modules::atmosphere_module());  // what god rays depend on
  world.modules().add_static(modules::godrays_module());
  world.modules().require_component("godrays.GodRays");
  int presets = 0;
  for (const auto& e : std::filesystem::directory_iterator(WELKIN_SOURCE_DIR "/modules/godrays/presets")) {
    if (e.path().extension() != ".json") continue;
    GodRays g;
    EXPECT_NO_THROW(object_from_json(type_desc<GodRays>(), &g, read_json_file(e.path().string()))) << e.path();
    const bool screen = e.path().filename().string().rfind("screen", 0) == 0;
    EXPECT_EQ(g.method, screen ? ShaftMethod::screen_space : ShaftMethod::marched) << e.path();
    ++presets;
  }
  EXPECT_GE(presets, 3);
}

}  // namespace
}  // namespace welkin::godrays

namespace welkin::modules {
const ModuleDefinition& terrain_module();
const ModuleDefinition& timeofday_module();
}  // namespace welkin::modules

namespace welkin::godrays {
namespace {

// The valley at sunset looking into the low sun under cumulus (assets/scenes/godrays-sunset.json),
// or at noon, with the god rays' method set, rendered alone at a small size.
// The godrays-sunset scene at 160x90 with the given shafts ("" for none) and a haze of the given
// density (negative for none).
ImageU8 valley(const std::string& method, double local_time_h, double haze_density = -1.0) {
  gl_context().make_current();
  World world;
  for (const ModuleDefinition* m : {&modules::atmosphere_module(), &modules::terrain_module(), &modules::timeofday_module(),
                                    &modules::clouds_module(), &modules::godrays_module()})
    world.modules().add_static(*m);
  json doc = read_json_file(WELKIN_SOURCE_DIR "/assets/scenes/godrays-sunset.json");
  for (auto& e : doc["entities"]) {  // the scene names the terrain relative to the repository root
    json& c = e["components"];
    if (c.contains("terrain.Terrain")) c["terrain.Terrain"]["file"] = WELKIN_SOURCE_DIR "/assets/terrain/valley.glb";
    if (c.contains("godrays.GodRays")) {
      if (method.empty()) c.erase("godrays.GodRays");
      else c["godrays.GodRays"]["method"] = method;
    }
    if (c.contains("timeofday.TimeOfDay")) c["timeofday.TimeOfDay"]["local_time_h"] = local_time_h;
  }
  if (haze_density >= 0.0)
    doc["entities"].push_back({{"name", "haze"}, {"components", {{"godrays.Haze", {{"density_per_m", haze_density}}}}}});
  load_scene(world, doc, "godrays-sunset.json");
  Renderer r(world);
  r.render_frame({.index = 1, .alone = true}, 160, 90);
  return r.read_output();
}

// Each path at sunset, the marched shafts at noon (the sun is off the screen: no screen-space pass),
// and the haze with the marched shafts at sunset.
TEST(GodRaysGolden, EachPathAtSunsetAndNoon) {
  const welkin::testing::GoldenTolerance tolerance{.max_channel_difference = 10, .max_failing_fraction = 0.02};
  for (const auto& [method, hour, name] : {std::tuple{"marched", 20.6, "godrays/sunset_marched"},
                                           std::tuple{"screen_space", 20.6, "godrays/sunset_screen_space"},
                                           std::tuple{"marched", 13.0, "godrays/noon_marched"}}) {
    const auto res = welkin::testing::compare_with_golden(valley(method, hour), name, tolerance);
    EXPECT_TRUE(res.passed) << name << ": " << res.message;
  }
  const auto res = welkin::testing::compare_with_golden(valley("marched", 20.6, 1e-4), "godrays/sunset_haze", tolerance);
  EXPECT_TRUE(res.passed) << "godrays/sunset_haze: " << res.message;
}

// Without haze the screen-space shafts are applied tile by tile, skipping tiles where they are zero;
// with a haze of density 0 (which changes nothing) the application covers the whole screen. Both
// must give the same frame, and it must differ from the frame without shafts.
TEST(GodRays, TheScreenSpaceTilesLeaveTheFrameAsTheWholeScreenDoes) {
  const ImageU8 tiled = valley("screen_space", 20.6), whole = valley("screen_space", 20.6, 0.0), none = valley("", 20.6);
  ASSERT_EQ(tiled.rgba.size(), whole.rgba.size());
  int differing = 0, shafted = 0;
  for (size_t i = 0; i < tiled.rgba.size(); ++i) {
    differing += std::abs(int(tiled.rgba[i]) - int(whole.rgba[i])) > 1;
    shafted += tiled.rgba[i] != none.rgba[i];
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(shafted, int(tiled.rgba.size() / 20)) << "the shafts change at least 5% of the channels";
}

}  // namespace
}  // namespace welkin::godrays

namespace welkin::godrays {
namespace {

// Optical depth of an exponential layer along a ray on the curved planet (the altitude exact), by
// Simpson's rule in double precision, to the ground or 400 km.
double layer_optical_depth(const glm::dvec3& camera_m, const glm::dvec3& dir, double radius_m, double density,
                           double scale_height_m) {
  const double b = glm::dot(camera_m, dir), c = glm::dot(camera_m, camera_m) - radius_m * radius_m;
  const double disc = b * b - c;
  const double end = (b < 0.0 && disc >= 0.0) ? -b - std::sqrt(disc) : 4.0e5;
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = end * i / n, h = glm::length(camera_m + t * dir) - radius_m;
    sum += (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0) * density * std::exp(-h / scale_height_m);
  }
  return sum * end / (3.0 * n);
}

// A haze that only absorbs scales the frame by its transmittance: against the optical depth on the
// curved planet, within 1% where the ray meets the ground within 9 km (the shader takes the layer as
// flat along a ray); the sky's rows within 5% from 6 degrees above the horizon up (at 3 degrees the
// flat layer makes the haze 8% too opaque).
TEST(GodRaysHaze, AnAbsorbingHazeScalesTheFrameByItsTransmittance) {
  const double density = 2e-4, scale_height = 800.0;
  const json haze = {{"density_per_m", density}, {"scale_height_m", scale_height}, {"scattering", 0.0}, {"absorption", 1.0}};
  json view = {{"position_m", {0, 0, 300}}, {"heading_deg", 30}, {"pitch_deg", 1}, {"vertical_fov_deg", 20}, {"ev100", 14}};
  auto doc = [&](bool with) {
    json c = {{"core.Camera", view}, {"atmosphere.Atmosphere", json::object()},
              {"atmosphere.Sun", {{"azimuth_deg", 10}, {"elevation_deg", 35}}}};
    if (with) c["godrays.Haze"] = haze;
    return scene(c);
  };
  Render without = render(doc(false), kW, kH), with = render(doc(true), kW, kH);
  ASSERT_TRUE(with.ran("godrays.apply"));
  EXPECT_FALSE(with.ran("godrays.shafts")) << "haze alone draws no shafts";
  const ImageF a = without.renderer->read_hdr(), b = with.renderer->read_hdr();
  World& w = *with.world;
  const FrameView& v = w.resource<RenderContext>().view;
  const double radius = 6360000.0;
  const glm::dvec3 camera(0.0, 0.0, radius + 300.0);
  int ground_rows = 0, sky_rows = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; x += 7) {
      const glm::dvec3 dir = glm::normalize(glm::dvec3(pixel_direction(v, x + 0.5, y + 0.5)));
      const bool ground = dir.z < -0.035, sky = dir.z > 0.1;
      if (!ground && !sky) continue;
      const double expected = std::exp(-layer_optical_depth(camera, dir, radius, density, scale_height));
      const double got = double(b.pixel(x, y)[1]) / double(a.pixel(x, y)[1]);
      EXPECT_NEAR(got, expected, (ground ? 0.01 : 0.05) * expected) << "pixel " << x << "," << y << " dir.z " << dir.z;
      (ground ? ground_rows : sky_rows) += x == 0;
    }
  EXPECT_GE(ground_rows, 3);
  EXPECT_GE(sky_rows, 3);
}

// A scattering haze adds light and dims what lies behind: stays finite and non-negative at the
// extremes (dense, thin, the camera in and far above it).
TEST(GodRaysHaze, ExtremeHazeStaysFiniteAndNonNegative) {
  for (const json& haze : {json{{"density_per_m", 1.0}, {"scale_height_m", 1.0}}, json{{"density_per_m", 1.0}, {"scale_height_m", 100000.0}},
                           json{{"density_per_m", 0.0}}, json{{"density_per_m", 1e-3}, {"phase_g", 0.999}}})
    for (double altitude : {0.0, 300.0, 5.0e5}) {
      json c = {{"core.Camera", {{"position_m", {0, 0, altitude}}, {"pitch_deg", -20}, {"vertical_fov_deg", 90}}},
                {"atmosphere.Atmosphere", json::object()}, {"atmosphere.Sun", {{"azimuth_deg", 0}, {"elevation_deg", 10}}},
                {"godrays.Haze", haze}, {"godrays.GodRays", {{"steps", 4}}}};
      Render r = render(scene(c), 16, 16);
      for (float value : r.renderer->read_hdr().rgba) {
        ASSERT_TRUE(std::isfinite(value)) << haze.dump() << " at " << altitude << " shafts " << r.ran("godrays.shafts");
        ASSERT_GE(value, -1e-3f) << haze.dump() << " at " << altitude;
      }
    }
}

// The frame block, declared once for C++ and GLSL (shaders/godrays/blocks.glsl.h): every 32-bit word
// written from C++ (each a distinct float) comes back from a std140 uniform block where C++ put it.
TEST(GodRaysGpuBlocks, EveryFieldOfTheFrameBlockReadsBackFromAStd140UniformBlock) {
  gl_context().make_current();
  const std::string header =
      read_file_text(WELKIN_SOURCE_DIR "/modules/godrays/shaders/godrays/blocks.glsl.h", 1u << 20);
  FrameBlock block{};
  std::vector<uint32_t> words(sizeof(FrameBlock) / 4);
  for (size_t i = 0; i < words.size(); ++i) {
    const float v = 1.5f * float(i + 1);
    std::memcpy(&words[i], &v, 4);
  }
  std::memcpy(static_cast<void*>(&block), words.data(), sizeof(FrameBlock));
  EXPECT_EQ(welkin::test::read_back_block(header, "GodRaysFrameGpu", &block, sizeof(FrameBlock), 1, true), words);
}

}  // namespace
}  // namespace welkin::godrays

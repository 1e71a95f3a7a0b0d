// The clouds module on llvmpipe: only what a scene needs runs and compiles, the noise is
// deterministic, tileable and made once, coverage means the fraction of sky covered, clouds darken
// the materials under them through the light environment, and the march converges as steps grow.
#include <algorithm>
#include <array>

#include "clouds_test_support.h"
#include "validation/cloud_field.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/scene/field_path.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;
using test::noon;
using test::render;
using test::stats;

TEST(CloudsGpu, ASceneWithoutCloudsLoadsNoCloudModuleAndCompilesNoCloudCode) {
  test::Rendered plain = render(test::scene({{"core.Camera", json::object()}, {"atmosphere.Atmosphere", json::object()},
                                             {"atmosphere.Sun", json::object()}}));
  EXPECT_FALSE(plain.world->modules().is_loaded("clouds"));
  const std::string lighting = plain.world->resource<LightEnvironment>().composed_source();
  EXPECT_EQ(lighting.find("clouds"), std::string::npos) << lighting;
  for (const auto& t : plain.last.timings) EXPECT_EQ(t.name.rfind("clouds.", 0), std::string::npos) << t.name;

  test::Rendered cloudy = render(noon());
  EXPECT_TRUE(cloudy.world->modules().is_loaded("clouds"));
  EXPECT_NE(cloudy.world->resource<LightEnvironment>().composed_source().find("clouds_light_visibility"), std::string::npos);
  EXPECT_TRUE(cloudy.ran("clouds.march"));
  EXPECT_TRUE(cloudy.ran("clouds.shadow_map"));
}

TEST(CloudsGpu, CoverageZeroMarchesNothingAndLeavesTheFrameAsWithoutClouds) {
  test::Rendered r = render(noon({{"coverage", 0.0}}));
  EXPECT_FALSE(r.ran("clouds.march"));
  EXPECT_FALSE(r.ran("clouds.shadow_map"));
  const ImageF with_module = r.renderer->read_hdr();
  test::Rendered clear = render(test::scene({{"core.Camera", {{"position_m", {0, 0, 100}}, {"heading_deg", 210}, {"pitch_deg", 10}, {"ev100", 14}}},
                                             {"atmosphere.Atmosphere", json::object()},
                                             {"atmosphere.Sun", {{"azimuth_deg", 240}, {"elevation_deg", 40}}}}));
  const ImageF without = clear.renderer->read_hdr();
  ASSERT_EQ(with_module.rgba.size(), without.rgba.size());
  for (size_t i = 0; i < without.rgba.size(); ++i) ASSERT_EQ(with_module.rgba[i], without.rgba[i]) << i;
}

TEST(CloudsGpu, ShadowsOnlyFromLayersThatCastThem) {
  json layers = json::array({{{"casts_shadow", false}}});
  test::Rendered r = render(noon({{"layers", layers}}));
  EXPECT_TRUE(r.ran("clouds.march"));
  EXPECT_FALSE(r.ran("clouds.shadow_map"));
}

TEST(CloudsGpu, NoiseIsMadeOnceDeterministicFromTheSeedAndTileable) {
  test::Rendered a = render(noon());
  a.frame(32, 18);
  a.frame(32, 18);
  auto& gpu = a.world->resource<CloudsGpu>();
  EXPECT_EQ(gpu.noise_builds, 1);
  const NoiseVolumes na = read_noise(gpu);
  test::Rendered b = render(noon());
  EXPECT_EQ(read_noise(b.world->resource<CloudsGpu>()).shape, na.shape);
  test::Rendered c = render(noon({{"seed", 7}}));
  const NoiseVolumes nc = read_noise(c.world->resource<CloudsGpu>());
  EXPECT_NE(nc.shape, na.shape);
  EXPECT_NE(nc.weather, na.weather);

  // Tileable: the step from the last slice to the first is like any step between neighbours.
  const int n = na.shape_size;
  auto at = [&](int x, int y, int z) { return double(na.shape[(size_t(z) * n + y) * n + x]); };
  double across = 0.0, inside = 0.0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y) across += std::abs(at(n - 1, y, z) - at(0, y, z)), inside += std::abs(at(n / 2, y, z) - at(n / 2 + 1, y, z));
  EXPECT_LT(across, 1.5 * inside);
  EXPECT_GT(inside, 0.0);
}

TEST(CloudsGpu, WeatherChannelsAreEqualisedSoCoverageIsTheCoveredFraction) {
  test::Rendered r = render(noon());
  const NoiseVolumes n = read_noise(r.world->resource<CloudsGpu>());
  for (int c = 0; c < 3; ++c)
    for (double q : {0.1, 0.3, 0.5, 0.9}) {
      size_t below = 0, count = n.weather.size() / 4;
      for (size_t i = 0; i < count; ++i) below += n.weather[i * 4 + size_t(c)] / 255.0 < q;
      EXPECT_NEAR(double(below) / double(count), q, 0.02) << "channel " << c << " quantile " << q;
    }
}

TEST(CloudsGpu, OvercastDarkensTheGroundThroughTheLightEnvironment) {
  // A grey ball on the ground, lit by the sun and the sky; an overcast deck above it.
  auto doc = [](double coverage) {
    json d = noon({{"layers", json::array({{{"genus", "stratus"}, {"coverage", 1.0}, {"base_altitude_m", 800}, {"thickness_m", 600}, {"density_per_m", 0.03}}})},
                   {"coverage", coverage}});
    d["entities"].push_back({{"name", "ball"}, {"components", {{"core.DebugShape", {{"position_m", {0, -30, 100}}, {"size_m", {5, 5, 5}}, {"albedo", {0.5, 0.5, 0.5}}}}}}});
    for (auto& e : d["entities"])
      if (e["components"].contains("core.Camera")) e["components"]["core.Camera"]["heading_deg"] = 180, e["components"]["core.Camera"]["pitch_deg"] = 0;
      else if (e["components"].contains("atmosphere.Sun")) e["components"]["atmosphere.Sun"]["azimuth_deg"] = 0;  // behind the camera
    return d;
  };
  test::Rendered clear = render(doc(0.0), 48, 27), overcast = render(doc(1.0), 48, 27);
  const ImageF a = clear.renderer->read_hdr(), b = overcast.renderer->read_hdr();
  // The ball's centre pixel (the camera looks south, straight at it).
  const size_t centre = (size_t(13) * 48 + 24) * 4;
  const float lit = a.rgba[centre + 1], shaded = b.rgba[centre + 1];
  EXPECT_GT(lit, 0.0f);
  // The deck (optical depth ~10-18) blocks the direct sun, but a conservative slab lets a diffuse
  // 1 / (1 + 0.75 (1 - g) tau) ~ 30% of the light through: dimmer, never black.
  EXPECT_LT(shaded, 0.5f * lit);
  EXPECT_GT(shaded, 0.1f * lit);
}

}  // namespace
}  // namespace welkin::clouds

namespace welkin::clouds {
namespace {

// The shadow map is remade only when what it shows changes: not for a still frame, yes for a sun
// that moved; and the map made earlier stays anchored where it was made.
TEST(CloudsGpu, ShadowMapIsRebuiltOnlyWhenItsInputsChange) {
  test::Rendered r = test::render(test::noon());
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  EXPECT_EQ(gpu.shadow_builds, 1);
  r.frame(32, 18);
  r.frame(32, 18);
  EXPECT_EQ(gpu.shadow_builds, 1);
  EXPECT_FALSE(r.ran("clouds.shadow_map"));
  r.camera().position_m.x += 50.0;  // a fraction of a texel's worth of the map's middle
  r.frame(32, 18);
  EXPECT_EQ(gpu.shadow_builds, 1);
  EXPECT_NEAR(gpu.shadow.origin.x, -50.0f, 1e-3f);
  auto& reg = r.world->registry();
  const ComponentInfo* sun = r.world->modules().component("atmosphere.Sun");
  resolve_field(*sun->type, reg.get(reg.pool(sun->type->id)->entities()[0], sun->type->id), "elevation_deg").set_scalar(41.0);
  r.frame(32, 18);
  EXPECT_EQ(gpu.shadow_builds, 2);
  r.clouds().layers[0].coverage = 0.2f;
  r.frame(32, 18);
  EXPECT_EQ(gpu.shadow_builds, 3);
}

}  // namespace
}  // namespace welkin::clouds

namespace welkin::clouds {
namespace {

// With no history yet (the first frame, as `welkin render` draws) every pixel is marched: the frame
// equals one drawn without temporal upscaling, bit for bit.
TEST(CloudsGpu, FirstTemporalFrameMarchesEveryPixel) {
  test::Rendered with = test::render(test::noon(), 48, 27);
  test::Rendered without = test::render(test::noon({{"temporal_upscaling", false}}), 48, 27);
  const ImageF a = with.renderer->read_hdr(), b = without.renderer->read_hdr();
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) differing += a.rgba[i] != b.rgba[i];
  EXPECT_EQ(differing, 0u);
  EXPECT_TRUE(with.ran("clouds.resolve"));
}

}  // namespace
}  // namespace welkin::clouds

// The genera's own shapes (welkin/clouds/genera.h) through the CPU mirror of the field (the GPU's own
// noise, read back): cirrus streaks along its wind, a cumulonimbus spreads into an anvil under its
// ceiling, and the genera without either pack and compile exactly as before.
#include <cmath>
#include <cstdio>

#include "clouds_test_support.h"
#include "density_field.h"
#include "validation/cloud_field.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;

struct Layer {
  test::Rendered rendered;
  std::unique_ptr<CloudField> field;
  LayerBlock block;
};

// One layer of `genus` at a base and thickness, the camera at the scene's origin on the ground.
Layer layer(const std::string& genus, double base_m, double thickness_m, double coverage, json wind) {
  json d = test::noon({{"temporal_upscaling", false},
                       {"layers", json::array({{{"genus", genus}, {"coverage", coverage}, {"base_altitude_m", base_m},
                                                {"thickness_m", thickness_m}, {"base_variation_m", 0},
                                                {"wind_mps", wind}}})}});
  Layer L{test::render(d, 8, 4), nullptr, {}};
  const CloudsGpu& gpu = L.rendered.world->resource<CloudsGpu>();
  L.field = std::make_unique<CloudField>(read_noise(gpu), gpu.block, gpu.layers);
  L.block = gpu.layers.at(0);
  return L;
}

// The correlation of the extinction at height h between points `lag` apart along `dir` (horizontal),
// over a grid of side 40 km around the camera.
double correlation(const CloudField& f, double h, const glm::dvec3& lag) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  int n = 0;
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 80; ++i) {
      const glm::dvec3 x(-20000.0 + 500.0 * i + 17.0 * j, -20000.0 + 500.0 * j, h);
      const double a = f.extinction(x), b = f.extinction(x + lag);
      sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, ++n;
    }
  const double ma = sa / n, mb = sb / n;
  const double va = saa / n - ma * ma, vb = sbb / n - mb * mb;
  return va > 0.0 && vb > 0.0 ? (sab / n - ma * mb) / std::sqrt(va * vb) : 0.0;
}

TEST(CloudsGenera, CirrusStreaksAlongItsWind) {
  const Layer ci = layer("cirrus", 8500.0, 800.0, 0.35, {25.0, 5.0});
  const GenusTraits& g = genus_traits(Genus::cirrus);
  const glm::dvec3 along = glm::normalize(glm::dvec3(25.0, 5.0, 0.0)), across(-along.y, along.x, 0.0);
  EXPECT_NEAR(glm::length(glm::dvec3(ci.block.streak_axis) - along), 0.0, 1e-6);
  EXPECT_EQ(ci.block.streak, g.streak);
  EXPECT_NEAR(ci.block.hook_m, g.hook_s * std::sqrt(25.0 * 25.0 + 5.0 * 5.0), 1e-2);
  // Two kilometres apart, the cloud along the wind is much the same, across it another one.
  const double h = 8500.0 + 0.5 * 800.0 - 100.0;  // camera-relative (the camera 100 m up)
  const double c_along = correlation(*ci.field, h, 2000.0 * along);
  const double c_across = correlation(*ci.field, h, 2000.0 * across);
  std::printf("cirrus: correlation 2 km along the wind %.3f, across %.3f\n", c_along, c_across);
  EXPECT_GT(c_along, 0.5);
  EXPECT_LT(c_across, 0.5 * c_along);

  // Without wind there is no direction to streak along: cirrus is then as round as any genus.
  const Layer still = layer("cirrus", 8500.0, 800.0, 0.35, {0.0, 0.0});
  EXPECT_EQ(glm::length(still.block.streak_axis), 0.0f);
  EXPECT_EQ(still.block.hook_m, 0.0f);
  const double s_along = correlation(*still.field, h, 2000.0 * along);
  const double s_across = correlation(*still.field, h, 2000.0 * across);
  EXPECT_NEAR(s_along, s_across, 0.15);
}

// The covered fraction of the layer at height t (a fraction of its thickness), over a grid of side
// 120 km around the camera (the cumulonimbus's weather repeats every 100 km).
double covered(const Layer& L, double t) {
  int cloud = 0, n = 0;
  const double h = L.block.base_m + t * L.block.thickness_m - 100.0;
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i, ++n)
      cloud += L.field->extinction({-60000.0 + 1200.0 * i + 31.0 * j, -60000.0 + 1200.0 * j, h}) > 0.0;
  return double(cloud) / n;
}

TEST(CloudsGenera, CumulonimbusSpreadsIntoAFlatAnvilUnderItsCeiling) {
  const Layer cb = layer("cumulonimbus", 1000.0, 9000.0, 0.35, {8.0, 0.0});
  const GenusTraits& g = genus_traits(Genus::cumulonimbus);
  EXPECT_EQ(cb.block.anvil_start, g.anvil_start);
  EXPECT_EQ(cb.block.anvil_spread, g.anvil_spread);
  EXPECT_EQ(cb.block.streak, 1.0f);  // no streaks: it reads the noise where every genus does
  // The towers thin out as they rise (the domes' tops); under the ceiling the tallest spread out
  // wider than the towers are anywhere below the anvil; at the ceiling the top is flat (nothing above).
  const double base = covered(cb, 0.2), below = covered(cb, 0.65), anvil = covered(cb, 0.92), top = covered(cb, 0.999);
  std::printf("cumulonimbus: covered at 20%% %.3f, 65%% %.3f, 92%% %.3f, 99.9%% %.3f\n", base, below, anvil, top);
  EXPECT_GT(base, 0.2);
  EXPECT_LT(below, base);
  EXPECT_GT(anvil, 1.5 * below);
  EXPECT_GT(anvil, base);
  EXPECT_LT(top, 0.02);
}

// The other genera have neither: their layers pack streak 1 and no anvil, and their field compiles
// no code for either (they read the noise exactly as before).
TEST(CloudsGenera, TheOtherGeneraCompileNeitherStreaksNorAnvils) {
  for (const GenusTraits& g : kGenera) {
    if (g.streak > 1.0f || g.hook_s > 0.0f || g.anvil_start > 0.0f) continue;
    const Layer L = layer(g.name, 2000.0, 800.0, 0.5, {10.0, 0.0});
    EXPECT_EQ(L.block.streak, 1.0f) << g.name;
    EXPECT_EQ(L.block.hook_m, 0.0f) << g.name;
    EXPECT_EQ(L.block.anvil_start, 0.0f) << g.name;
    const ShaderDefines d = field_defines(L.rendered.world->resource<CloudsGpu>());
    EXPECT_EQ(d.at("CLOUDS_STREAKS"), "0") << g.name;
    EXPECT_EQ(d.at("CLOUDS_ANVILS"), "0") << g.name;
  }
}

}  // namespace
}  // namespace welkin::clouds

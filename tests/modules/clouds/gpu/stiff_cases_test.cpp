// Stiff and extreme inputs (issue 10, DESIGN.md Numerics): every frame stays finite, non-negative and
// below what the sun can deliver through the case's phase function; the march converges as its
// steps shrink. One world per case family, tiny frames on llvmpipe.
#include <functional>

#include "clouds_test_support.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;

struct StiffCase {
  std::string name;
  std::function<void(VolumetricClouds&, Camera&)> apply;
  float phase_peak = 1.0f;  // the case's largest phase value (1/sr), for the energy bound
};
void PrintTo(const StiffCase& c, std::ostream* os) { *os << c.name; }

float hg_peak(float g) { return (1.0f + std::abs(g)) / (4.0f * 3.14159265f * (1.0f - std::abs(g)) * (1.0f - std::abs(g))); }

class CloudsStiff : public ::testing::TestWithParam<StiffCase> {};

TEST_P(CloudsStiff, FrameIsFiniteNonNegativeAndBounded) {
  test::Rendered r = test::render(test::noon(), 24, 14);
  const ImageF clear = r.renderer->read_hdr();
  const test::ImageStats background = test::stats(clear);
  GetParam().apply(r.clouds(), r.camera());
  r.frame(24, 14);
  const test::ImageStats s = test::stats(r.renderer->read_hdr());
  EXPECT_TRUE(s.finite);
  EXPECT_GE(s.min, 0.0f);
  // Clouds scatter at most the sun's illuminance (120 klx) times the phase's peak per unit solid
  // angle, on top of whatever the sky behind them held.
  const float bound = background.max + 120000.0f * std::max(GetParam().phase_peak, hg_peak(0.7f));
  EXPECT_LE(s.max, bound);
}

std::vector<CloudLayer> many_layers(int n) {
  std::vector<CloudLayer> layers(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    layers[size_t(i)].base_altitude_m = 500.0f + 97.0f * float(i);
    layers[size_t(i)].thickness_m = 300.0f + 11.0f * float(i % 7);
    layers[size_t(i)].coverage = 0.1f + 0.008f * float(i);
    layers[size_t(i)].genus = Genus(i % kGenusCount);
  }
  return layers;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CloudsStiff,
    ::testing::Values(
        StiffCase{"coverage_1", [](VolumetricClouds& c, Camera&) { for (auto& l : c.layers) l.coverage = 1.0f; }},
        StiffCase{"density_x0", [](VolumetricClouds& c, Camera&) { for (auto& l : c.layers) l.density_per_m = 0.0f; }},
        StiffCase{"density_x1000", [](VolumetricClouds& c, Camera&) { for (auto& l : c.layers) l.density_per_m *= 1000.0f; }},
        StiffCase{"thickness_0", [](VolumetricClouds& c, Camera&) { for (auto& l : c.layers) l.thickness_m = 0.0f; }},
        // A 64-texel shadow map: 100 stacked layers fill every shadow column with cloud, and at the default
        // size (256) the case took 98 s on two cores, 19 s at 64.
        StiffCase{"layers_100", [](VolumetricClouds& c, Camera&) { c.layers = many_layers(100), c.shadow_map_size = 64; }},
        StiffCase{"camera_at_base", [](VolumetricClouds&, Camera& cam) { cam.position_m.z = 1500.0; }},
        StiffCase{"camera_inside", [](VolumetricClouds&, Camera& cam) { cam.position_m.z = 2100.0; }},
        StiffCase{"camera_on_top", [](VolumetricClouds&, Camera& cam) { cam.position_m.z = 3060.0, cam.pitch_deg = -30.0f; }},
        StiffCase{"camera_1000_km", [](VolumetricClouds&, Camera& cam) { cam.position_m.z = 1.0e6, cam.pitch_deg = -90.0f; }},
        StiffCase{"g_plus_0999", [](VolumetricClouds& c, Camera&) { c.phase_g_forward = 0.999f; }, hg_peak(0.999f)},
        StiffCase{"g_minus_0999", [](VolumetricClouds& c, Camera&) { c.phase_g_backward = -0.999f; }, hg_peak(0.999f)},
        StiffCase{"droplet_mie", [](VolumetricClouds& c, Camera&) { c.phase = PhaseModel::droplet_mie, c.droplet_diameter_um = 50.0f; }, hg_peak(0.99f)},
        StiffCase{"one_march_step", [](VolumetricClouds& c, Camera&) { c.quality = Quality::custom, c.max_steps = 1; }},
        StiffCase{"no_light_steps_one_octave", [](VolumetricClouds& c, Camera&) {
          c.quality = Quality::custom, c.light_steps = 0, c.multiscattering_octaves = 1; }},
        StiffCase{"all_absorbing", [](VolumetricClouds& c, Camera&) { c.scattering_coefficient = 0.0f, c.absorption_coefficient = 10.0f; }}),
    [](const auto& info) { return info.param.name; });

// The sun below the horizon needs its own scene: the sun is an atmosphere component.
TEST(CloudsStiffSun, SunFarBelowTheHorizonLeavesFiniteDarkClouds) {
  json doc = test::noon();
  for (auto& e : doc["entities"])
    if (e["components"].contains("atmosphere.Sun")) e["components"]["atmosphere.Sun"]["elevation_deg"] = -30;
  test::Rendered r = test::render(doc, 24, 14);
  const test::ImageStats s = test::stats(r.renderer->read_hdr());
  EXPECT_TRUE(s.finite);
  EXPECT_GE(s.min, 0.0f);
  EXPECT_LT(s.max, 1.0f);  // night: no sunlight anywhere (cd/m^2)
}

// Self-convergence: with steps of 400, 100 and 25 m the mean difference from a 6 m march shrinks.
TEST(CloudsConvergence, ErrorShrinksAsStepsShrink) {
  test::Rendered r = test::render(test::noon(), 24, 14);
  auto march = [&](float step_m) {
    VolumetricClouds& c = r.clouds();
    c.quality = Quality::custom, c.resolution_scale = 1.0f, c.max_steps = 4096, c.temporal_upscaling = false;
    c.min_step_m = c.max_step_m = step_m, c.max_distance_m = 30000.0f;
    r.frame(24, 14);
    return r.renderer->read_hdr();
  };
  const ImageF reference = march(6.0f);
  double previous = INFINITY;
  for (float step : {400.0f, 100.0f, 25.0f}) {
    const ImageF img = march(step);
    double error = 0.0, total = 0.0;
    for (size_t i = 0; i < img.rgba.size(); ++i)
      if (i % 4 != 3) error += std::abs(img.rgba[i] - reference.rgba[i]), total += reference.rgba[i];
    const double relative = error / total;
    EXPECT_LT(relative, previous) << "step " << step << " m";
    previous = relative;
  }
  EXPECT_LT(previous, 0.02);
}

}  // namespace
}  // namespace welkin::clouds

// The GPU march against the path-traced reference through the same field (validation/cloud_probe.h), on
// rays from below, inside and above a cumulus layer. The full sweep with run times is
// `welkin accuracy clouds`; here a handful of rays guard the figures docs/clouds.md states.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "clouds_test_support.h"
#include "validation/cloud_probe.h"
#include "scratch_folder.h"

namespace welkin::clouds {
namespace {

VolumetricClouds cumulus() {
  VolumetricClouds c;
  c.layers = {CloudLayer{.genus = Genus::cumulus, .base_altitude_m = 1500.0f, .thickness_m = 1200.0f, .coverage = 0.6f, .density_per_m = 0.03f}};
  c.shadows = true;  // the march reads the optical depth beyond its light steps from the shadow map
  // The field docs/clouds.md's figures were measured on: the layer's own coverage everywhere (with the
  // weather systems' slight change of the coverage the worst ray, a base, is 37% too bright).
  c.weather_system_amount = 0.0f;
  return c;
}

// Sun 40 degrees up; views from below (the base), inside and above (the lit tops and the side away).
const CloudView kViews[] = {{"below 60", 100, 0, 60}, {"below 30", 100, 90, 30}, {"below 85", 100, 180, 85},
                            {"inside", 2000, 30, 10}, {"above", 4000, 0, -40},  {"above sun side", 4000, 200, -20}};

TEST(CloudsAccuracy, DiffusionBeatsOctavesAndStaysWithinItsStatedError) {
  test::gl_context().make_current();
  CloudProbe probe(cumulus(), 200.0, 40.0);
  reference::PathTraceSettings s;
  s.samples = 4096;  // the darker bases of the eroded field: at 2048 paths a base's 95% interval is 12%
  double sum[2] = {0.0, 0.0}, worst[2] = {0.0, 0.0};
  for (const CloudView& v : kViews) {
    const auto ref = probe.reference_radiance(v, s);
    ASSERT_LT(ref.scattered.ci95, 0.1 * ref.radiance()) << v.name;
    for (int m = 0; m < 2; ++m) {
      probe.clouds().multiple_scattering = MultipleScattering(m);
      const double gpu = probe.gpu_radiance(v), e = (gpu - ref.radiance()) / ref.radiance();
      sum[m] += e * e, worst[m] = std::max(worst[m], std::abs(e));
      std::printf("%-16s %-9s gpu %9.1f  reference %9.1f +- %6.1f  (%+.1f%%)\n", v.name.c_str(), m ? "diffusion" : "octaves",
                  gpu, ref.radiance(), ref.scattered.ci95, 100.0 * e);
    }
  }
  const double n = double(std::size(kViews));
  const double rmse_octaves = std::sqrt(sum[0] / n), rmse_diffusion = std::sqrt(sum[1] / n);
  std::printf("relative RMSE: octaves %.1f%% (worst %.1f%%), diffusion %.1f%% (worst %.1f%%)\n", 100 * rmse_octaves,
              100 * worst[0], 100 * rmse_diffusion, 100 * worst[1]);
  EXPECT_LT(rmse_diffusion, rmse_octaves);
  // Measured with the fitted light model (light_model_fit.glsl, docs/clouds-light.md), fitted on this
  // cumulus, two stratus decks and a cumulus under a low sun: 16.2%, worst 24.8% (a base seen 60
  // degrees up, too dark); 16.6%, worst 26.1% once the march kept its jitter through empty strides
  // (the mean of 16 frames: CloudProbe::kJitterFrames). The model fitted on this cumulus alone measured 7.6%, worst 12.6%, and was
  // two to ten times too bright on decks under a low sun (the test below); over the fit's 20 cumulus
  // rays the two are alike (13.6%). The seven-coefficient model: 9.5%, worst 15.2%; the hand-set
  // model: 14.6%, worst 30.8%.
  // On the eroded field (billowed tops, wispy bases: docs/clouds.md, "Shape"), refitted on it: 37.6%,
  // worst 86.0% (the side away from the sun seen from above, too bright: light that the path tracer
  // loses through the gaps between the billows; the bases within 3-20%). With the terms that weigh the
  // diffuse light by how much of the un-eroded envelope the noise left at the sample (30, 31): 29.8%,
  // worst 64.6% (that side still, too bright; the top -21.7%, the base 30 degrees up -20.7%).
  // With the shadow map's columns kept by their optical depth's knots (clouds/shadow_column.glsl; a
  // beer map spread a column's far clouds over its near ones): 33.2%, worst 73.8%, the same side
  // brighter by a tenth: the weights had been fitted against the beer map's darker light. Refitted
  // with the knots (docs/clouds-light.md, "Low suns"), 35.5-36.7%, worst 81-84% on this side, while
  // the fit's own sets and the peer image got better: not adopted.
  EXPECT_LT(rmse_diffusion, 0.345);
  EXPECT_LT(worst[1], 0.76);
}

// A stratus deck (0.8-1.3 km, coverage 0.9) under a sun 12 degrees up: the bases' multiple scattering
// comes through the whole column (diffusion theory's mu_0 per unit area of the lit top), not along the
// slant path toward the sun; a model fitted on a cumulus under a high sun alone lights the deck two
// to five times too bright.
TEST(CloudsAccuracy, DeckUnderALowSunStaysWithinItsStatedError) {
  test::gl_context().make_current();
  VolumetricClouds deck;
  deck.layers = {CloudLayer{.genus = Genus::stratus, .base_altitude_m = 800.0f, .thickness_m = 500.0f, .coverage = 0.9f, .density_per_m = 0.03f}};
  deck.weather_system_amount = 0.0f;
  CloudProbe probe(deck, 200.0, 12.0);
  reference::PathTraceSettings s;
  s.samples = 8192;  // a deck's base is dim: at 4096 paths its 95% interval is 15% of its radiance
  const CloudView views[] = {{"below 30", 200, 0, 30}, {"below 70", 200, 200, 70}, {"inside", 1050, 20, 5, 300, 200},
                             {"above", 2500, 200, -40}};
  // Errors relative to the mean reference over the rays (as `welkin accuracy clouds` and the fit
  // weigh them): the bases are a fifth as bright as the top.
  std::vector<double> gpu, ref;
  for (const CloudView& v : views) {
    const auto r = probe.reference_radiance(v, s);
    ASSERT_LT(r.scattered.ci95, 0.15 * r.radiance()) << v.name;
    gpu.push_back(probe.gpu_radiance(v)), ref.push_back(r.radiance());
    std::printf("%-10s gpu %9.1f  reference %9.1f +- %6.1f\n", v.name.c_str(), gpu.back(), ref.back(), r.scattered.ci95);
  }
  double mean = 0.0, sum = 0.0, worst = 0.0;
  for (double r : ref) mean += r / double(ref.size());
  for (size_t i = 0; i < ref.size(); ++i) {
    const double e = (gpu[i] - ref[i]) / mean;
    sum += e * e, worst = std::max(worst, std::abs(e));
  }
  const double rmse = std::sqrt(sum / double(ref.size()));
  std::printf("relative RMSE %.1f%% (worst %.1f%%)\n", 100 * rmse, 100 * worst);
  // Measured (docs/clouds-light.md): 4.9%, worst 7.5%; 7.6%, worst 12.4% once the march kept its
  // jitter through empty strides (the top seen from above 5% too bright, within the reference's 95%
  // interval; one jitter for every frame had put it at +1.7%); the model fitted on the cumulus alone,
  // on the same rays' marched terms: 201%, worst 364% (every ray too bright, the top from above most).
  // On the eroded field, refitted on it: 26.7%, worst 47.8% (the inside and the top too bright); with
  // the envelope's fill terms (30, 31): 20.5%, worst 30.5% (the inside 41% too bright, the top 12%).
  EXPECT_LT(rmse, 0.23);
  EXPECT_LT(worst, 0.33);
}

// A deck that casts no shadow over a layer that does (cirrus over cumulus; here a thin cirrostratus at
// 7.5-8 km over a haze at the ground), under a sun 10 degrees up: the haze's light under the deck,
// as a ratio to the same haze's without it, against the path tracer's ratio (the light model's own
// error on the haze cancels): the light a deck scatters forward and down is not lost to what lies under it.
TEST(CloudsAccuracy, ADeckOverTheShadowCastersDimsTheLightUnderItAsThePathTracerDoes) {
  test::gl_context().make_current();
  VolumetricClouds haze;
  haze.layers = {CloudLayer{.genus = Genus::stratus, .base_altitude_m = 0.0f, .thickness_m = 300.0f, .coverage = 1.0f,
                            .density_per_m = 0.0005f, .shape_amount = 0.2f, .detail_amount = 0.0f,
                            .coverage_filter_width = 1.0f, .base_variation_m = 0.0f, .profile_exp_term = 1.0f,
                            .profile_exponent = -3.0f, .profile_linear_term = 0.0f, .profile_constant_term = 0.0f}};
  haze.shadows = true;
  haze.weather_system_amount = 0.0f;
  VolumetricClouds decked = haze;
  decked.layers.push_back(CloudLayer{.genus = Genus::cirrostratus, .base_altitude_m = 7500.0f, .thickness_m = 500.0f,
                                     .coverage = 1.0f, .density_per_m = 0.0005f, .shape_amount = 0.4f,
                                     .detail_amount = 0.0f, .coverage_filter_width = 0.5f, .casts_shadow = false});
  CloudProbe alone(haze, 240.0, 10.0), under(decked, 240.0, 10.0);
  reference::PathTraceSettings s;
  s.samples = 8192;  // the haze across the sun's way is dim: at 2048 paths its 95% interval is 8%
  const CloudView views[] = {{"toward the sun", 280, 240, -2}, {"across", 280, 150, -2}, {"away", 280, 60, -2}};
  for (const CloudView& v : views) {
    const auto r0 = alone.reference_radiance(v, s), r1 = under.reference_radiance(v, s);
    ASSERT_LT(r1.scattered.ci95, 0.05 * r1.radiance()) << v.name;
    const double reference = r1.radiance() / r0.radiance(), gpu = under.gpu_radiance(v) / alone.gpu_radiance(v);
    std::printf("%-15s under the deck / without it: gpu %.3f, reference %.3f\n", v.name.c_str(), gpu, reference);
    // Measured: 1.09, 0.95 and 0.99 times the reference's ratio (references 0.59, 0.77, 0.69); with the
    // deck left out of the light, as before, 1.69, 1.30 and 1.45 times.
    EXPECT_NEAR(gpu / reference, 1.0, 0.25) << v.name;
  }
}

// The sky alone (CloudProbe::Light::sky: a uniform sky over a black ground, no sun) on the same rays:
// the march's ambient term against the light the path tracer's clouds scatter. Errors relative to the
// mean reference over the rays, as `welkin accuracy clouds` reports them.
TEST(CloudsAccuracy, TheSkyAloneFollowsThePathTracer) {
  test::gl_context().make_current();
  CloudProbe probe(cumulus(), 200.0, 40.0);
  probe.set_light(CloudProbe::Light::sky);
  reference::PathTraceSettings s;
  s.samples = 2048;
  std::vector<double> gpu, reference;
  double mean = 0.0;
  for (const CloudView& v : kViews) {
    const auto ref = probe.reference_radiance(v, s);
    EXPECT_EQ(ref.truncated_paths, 0u) << v.name;
    reference.push_back(ref.scattered.mean), gpu.push_back(probe.gpu_radiance(v));
    mean += reference.back() / double(std::size(kViews));
    std::printf("%-16s sky alone: gpu %8.1f  reference %8.1f +- %5.1f\n", v.name.c_str(), gpu.back(),
                reference.back(), ref.scattered.ci95);
  }
  double sum = 0.0, worst = 0.0;
  for (size_t i = 0; i < gpu.size(); ++i) {
    const double e = (gpu[i] - reference[i]) / mean;
    sum += e * e, worst = std::max(worst, std::abs(e));
  }
  const double rmse = std::sqrt(sum / double(gpu.size()));
  std::printf("the sky alone: relative RMSE %.1f%%, worst %.1f%%\n", 100 * rmse, 100 * worst);
  EXPECT_GT(mean, 100.0);  // the sky does light the clouds (25 klx over a plane facing up)
  // Measured: 6.4%, worst 14.5% (a base seen 60 degrees up, too bright; the references' own 95%
  // intervals are 1.5-5%); through the diffuse transmittance toward the sun, as before
  // clouds_ambient, 61.9%, worst 92.3% (every ray two to three times too dark). 6.1%, worst 13.6% once
  // the march kept its jitter through empty strides (the mean of 16 frames).
  // On the eroded field: 12.9%, worst 20.1% (the column's top over a sample is the rounded envelope's).
  EXPECT_LT(rmse, 0.14);
  EXPECT_LT(worst, 0.22);
}

// The reference cache: a ray path traced once is read back as it was (its stored run time with it),
// and a field the ray sees differently is path traced again under another key.
TEST(CloudsAccuracy, ReferenceCacheReadsTheSameRayBackAndMissesAChangedField) {
  test::gl_context().make_current();
  const std::filesystem::path folder = welkin::testing::scratch_folder("welkin-cloud-reference-cache-test") / "cache";
  std::filesystem::remove_all(folder);
  CloudProbe probe(cumulus(), 200.0, 40.0);
  probe.set_reference_cache(DiskCache(folder.string()));
  reference::PathTraceSettings s;
  s.samples = 256;
  const CloudView view = kViews[0];
  auto files = [&] { return std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()); };
  const auto computed = probe.reference_radiance(view, s);
  ASSERT_EQ(files(), 1);
  const auto read = probe.reference_radiance(view, s);
  EXPECT_EQ(read.scattered.mean, computed.scattered.mean);
  EXPECT_EQ(read.scattered.ci95, computed.scattered.ci95);
  EXPECT_EQ(read.transmittance.mean, computed.transmittance.mean);
  EXPECT_EQ(read.wall_ms, computed.wall_ms);  // not path traced again
  EXPECT_EQ(files(), 1);
  probe.clouds().layers[0].coverage = 0.5f;
  const auto changed = probe.reference_radiance(view, s);
  EXPECT_EQ(files(), 2);
  EXPECT_NE(changed.scattered.mean, computed.scattered.mean);
  std::filesystem::remove_all(folder);
}

// The reference image is cached whole: read back as it was, path traced again when the field changes.
TEST(CloudsAccuracy, ReferenceImageCacheReadsTheImageBackAndMissesAChangedField) {
  test::gl_context().make_current();
  const std::filesystem::path folder = welkin::testing::scratch_folder("welkin-cloud-image-cache-test") / "cache";
  std::filesystem::remove_all(folder);
  CloudProbe probe(cumulus(), 200.0, 40.0);
  probe.set_reference_cache(DiskCache(folder.string()));
  reference::PathTraceSettings s;
  s.samples = 16;
  Camera camera;
  camera.position_m = {0.0, 0.0, 100.0}, camera.heading_deg = 0.0f, camera.pitch_deg = 60.0f;
  auto files = [&] { return std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()); };
  const auto computed = probe.reference_image(camera, 4, 3, s);
  ASSERT_EQ(files(), 1);
  const auto read = probe.reference_image(camera, 4, 3, s);
  ASSERT_EQ(read.size(), computed.size());
  double light = 0.0;
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].scattered.mean, computed[i].scattered.mean) << i;
    EXPECT_EQ(read[i].wall_ms, computed[i].wall_ms) << i;  // not path traced again
    light += computed[i].scattered.mean;
  }
  EXPECT_GT(light, 0.0);  // the view sees cloud
  EXPECT_EQ(files(), 1);
  probe.clouds().layers[0].coverage = 0.5f;
  probe.reference_image(camera, 4, 3, s);
  EXPECT_EQ(files(), 2);
  std::filesystem::remove_all(folder);
}

// The march's image and the path tracer's run their rows the same way: level with the layer's base
// from 100 m, the top quarter of the view sees cloud in both and the bottom quarter (20-30 degrees
// down, the ground) in neither (the march's pixels between blur across the horizon: it runs at a
// quarter of the size and is magnified). The probe once turned the march's rows over, and every
// image figure compared the sky with the ground.
TEST(CloudsAccuracy, ProbeImagesRunTheirRowsTheSameWay) {
  test::gl_context().make_current();
  CloudProbe probe(cumulus(), 200.0, 40.0);
  reference::PathTraceSettings s;
  s.samples = 2;
  Camera camera;
  camera.position_m = {0.0, 0.0, 100.0}, camera.heading_deg = 0.0f, camera.pitch_deg = 0.0f;
  const int w = 16, h = 16;
  const std::vector<double> march = probe.gpu_image(camera, w, h);
  const auto traced = probe.reference_image(camera, w, h, s);
  double march_top = 0.0, march_bottom = 0.0, traced_top = 0.0, traced_bottom = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (y < h / 4) march_top += march[i], traced_top += traced[i].scattered.mean;
      if (y >= h - h / 4) march_bottom += march[i], traced_bottom += traced[i].scattered.mean;
    }
  EXPECT_GT(march_top, 0.0);
  EXPECT_GT(traced_top, 0.0);
  EXPECT_EQ(march_bottom, 0.0);
  EXPECT_EQ(traced_bottom, 0.0);
}

}  // namespace
}  // namespace welkin::clouds

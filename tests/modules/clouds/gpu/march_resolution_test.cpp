// The clouds' image mean with the temporal upscaling against the same march without it, on the peer
// scene's cumulus (takram's default layers, coverage 0.3, sun 10 degrees up) seen from 100 m,
// under the probe's light (validation/cloud_probe.h). Each image is the mean of 16 jittered frames.
// docs/clouds-light.md, "The peer scene's image", has the figures at 48x27 to 640x360.
#include <cstdio>
#include <vector>

#include "clouds_test_support.h"
#include "validation/cloud_probe.h"
#include "validation/isolated_pixels.h"

namespace welkin::clouds {
namespace {

VolumetricClouds peer_cumulus(Quality quality) {
  VolumetricClouds c;
  c.quality = quality;
  c.layers = {CloudLayer{.genus = Genus::cumulus,
                         .base_altitude_m = 750.0f,
                         .thickness_m = 650.0f,
                         .coverage = 0.3f,
                         .density_per_m = 0.05f},
              CloudLayer{.genus = Genus::cumulus,
                         .base_altitude_m = 1000.0f,
                         .thickness_m = 1200.0f,
                         .coverage = 0.3f,
                         .density_per_m = 0.05f}};
  return c;
}

Camera peer_camera() {
  Camera camera;
  camera.position_m = {0.0, 0.0, 100.0}, camera.heading_deg = 210.0f, camera.pitch_deg = 8.0f;
  camera.vertical_fov_deg = 60.0f;
  return camera;
}

double mean_of(const std::vector<double>& image) {
  double sum = 0.0;
  for (double v : image) sum += v;
  return sum / double(image.size());
}

// A march of the preset's steps and light at `scale` of the frame's pixels, without the upscaling.
void march_at(VolumetricClouds& c, float scale) {
  const ResolvedQuality q = resolve_quality(c);
  c.quality = Quality::custom;
  c.max_steps = q.max_steps, c.min_step_m = q.min_step_m, c.max_step_m = q.max_step_m;
  c.light_steps = q.light_steps, c.light_step_m = q.light_step_m, c.shape_detail = q.shape_detail;
  c.step_growth = q.step_growth, c.turbulence = q.turbulence;
  c.resolution_scale = scale, c.temporal_upscaling = false;
}

// A still view's temporal upscaling keeps its own march: the fresh samples differ from their history by
// the march's jitter alone, which moves a thin sunlit edge's sample by all of its value. Read as change,
// it clipped the history toward the sparse samples around it (4 x 4 blocks at `low`) frame after frame:
// over 16 frames at 96x54 the upscaled frame's mean was 61% of the same march's without the upscaling
// (94% with the history kept unclipped in a held view: the first partial frame still clips). Every
// value finite; the holes and fireflies (validation/isolated_pixels.h) are printed.
TEST(CloudsMarchResolution, AStillViewsUpscalingKeepsTheMarchsMean) {
  test::gl_context().make_current();
  CloudProbe probe(peer_cumulus(Quality::low), 240.0, 10.0);
  const int w = 96, h = 54;
  probe.clouds().temporal_upscaling = true;
  const std::vector<double> upscaled = probe.gpu_image(peer_camera(), w, h);
  march_at(probe.clouds(), resolve_quality(peer_cumulus(Quality::low)).resolution_scale);
  const double marched = mean_of(probe.gpu_image(peer_camera(), w, h));
  ASSERT_GT(marched, 0.0);
  const IsolatedPixels n = count_isolated_pixels(upscaled, w, h, 0.02 * marched);
  std::printf(
      "upscaled at low, %dx%d: mean %.1f%% of the march's without the upscaling; %d holes, %d fireflies\n", w,
      h, 100.0 * mean_of(upscaled) / marched, n.holes, n.fireflies);
  EXPECT_GT(mean_of(upscaled) / marched, 0.9);
  EXPECT_LT(mean_of(upscaled) / marched, 1.1);
  EXPECT_EQ(n.not_finite, 0);
}

}  // namespace
}  // namespace welkin::clouds

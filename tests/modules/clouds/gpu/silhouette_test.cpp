// Silhouettes after the temporal upscaling (issue 35): frames upscaled from one pixel of each block
// per frame against a march of every pixel of the same view (temporal upscaling off, the same
// quality otherwise), still and flying, after the history settled. Measured where the full march
// changes between neighbours (its silhouettes) and over the frame.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "clouds_test_support.h"

namespace welkin::clouds {
namespace {

struct EdgeError {
  double silhouette = 0.0;  // mean |upscaled - full| / mean full luminance, at silhouette pixels
  double frame = 0.0;       // relative L1 over the frame
  size_t silhouette_pixels = 0;
};

double luminance(const ImageF& im, int x, int y) {
  const float* p = &im.rgba[(size_t(y) * im.width + x) * 4];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// Silhouette pixels: where the full march's luminance differs from a neighbour's by more than a
// quarter of the frame's mean (the clouds' edges against the sky; the ground's horizon too).
EdgeError edge_error(const ImageF& upscaled, const ImageF& full) {
  double mean = 0.0;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) mean += luminance(full, x, y);
  mean /= double(full.width) * full.height;
  EdgeError e;
  double edge_sum = 0.0, frame_sum = 0.0, frame_total = 0.0;
  for (int y = 1; y + 1 < full.height; ++y)
    for (int x = 1; x + 1 < full.width; ++x) {
      const double l = luminance(full, x, y);
      const double step =
          std::max({std::abs(l - luminance(full, x + 1, y)), std::abs(l - luminance(full, x - 1, y)),
                    std::abs(l - luminance(full, x, y + 1)), std::abs(l - luminance(full, x, y - 1))});
      const double d = std::abs(luminance(upscaled, x, y) - l);
      frame_sum += d, frame_total += l;
      if (step > 0.25 * mean) edge_sum += d, ++e.silhouette_pixels;
    }
  e.silhouette = edge_sum / std::max<size_t>(e.silhouette_pixels, 1) / mean;
  e.frame = frame_sum / frame_total;
  return e;
}

// A crop of the frame, tone mapped by exposure (x4 nearest, to see the pixels), when
// WELKIN_TEST_IMAGES names a folder.
float exposure_of(const ImageF& im) {  // the frame's mean lands at mid grey
  double mean = 0.0;
  for (size_t i = 0; i < im.rgba.size(); ++i) mean += i % 4 == 3 ? 0.0 : im.rgba[i];
  return float(0.75 * 3.0 * im.width * im.height / std::max(mean, 1e-30));
}

void write_crop(const ImageF& im, const std::string& name, float exposure = 0.0f) {
  const char* dir = std::getenv("WELKIN_TEST_IMAGES");
  if (!dir) return;
  const int s = 4;
  if (exposure == 0.0f) exposure = exposure_of(im);
  ImageU8 out{im.width * s, im.height * s,
              std::vector<uint8_t>(size_t(im.width) * im.height * s * s * 4, 255)};
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = exposure * im.rgba[(size_t(y / s) * im.width + x / s) * 4 + c];
        const float mapped = std::pow(v / (1.0f + v), 1.0f / 2.2f);
        out.rgba[(size_t(y) * out.width + x) * 4 + c] =
            uint8_t(std::clamp(mapped, 0.0f, 1.0f) * 255.0f + 0.5f);
      }
  write_png((std::filesystem::path(dir) / (name + ".png")).string(), out);
}

// The camera flies 45 m a frame, climbing, and turns 0.6 degrees a frame (as `welkin accuracy
// clouds`'s ghosting measure); frames 0-3 fill the history; `frames` more are measured.
EdgeError measure(bool flying, int frames, const std::string& name) {
  const int w = 128, h = 72;
  auto doc = [](bool temporal) {
    nlohmann::json d = test::noon({{"quality", "high"}, {"temporal_upscaling", temporal}});
    test::entity_with(d, "core.Camera")["components"]["core.Camera"]["moving_render_scale"] = 1.0;
    return d;
  };
  test::Rendered upscaled = test::render(doc(true), w, h), full = test::render(doc(false), w, h);
  EdgeError sum, floor;
  int counted = 0;
  ImageF previous_full;
  for (int f = 1; f < 4 + frames; ++f) {
    for (test::Rendered* r : {&upscaled, &full}) {
      if (flying) {
        r->camera().position_m = {-20.0 * f, -40.0 * f, 100.0 + 5.0 * f};
        r->camera().heading_deg = 210.0f + 0.6f * float(f);
      }
      r->frame(w, h);
    }
    if (f < 4) continue;
    const ImageF a = upscaled.renderer->read_hdr(), b = full.renderer->read_hdr();
    const EdgeError e = edge_error(a, b);
    // The floor: a still view's full march against the same march one frame (one jitter) earlier.
    if (!flying && !previous_full.rgba.empty()) {
      const EdgeError j = edge_error(previous_full, b);
      floor.silhouette += j.silhouette, floor.frame += j.frame;
    }
    previous_full = b;
    sum.silhouette += e.silhouette, sum.frame += e.frame, sum.silhouette_pixels += e.silhouette_pixels;
    ++counted;
    if (f == 3 + frames) {
      write_crop(a, name + "-upscaled"), write_crop(b, name + "-full");
      ImageF difference = b;  // |upscaled - full|, x4 against the frame
      for (size_t i = 0; i < b.rgba.size(); ++i)
        difference.rgba[i] = i % 4 == 3 ? 1.0f : std::abs(a.rgba[i] - b.rgba[i]);
      write_crop(difference, name + "-difference", exposure_of(b) * 4.0f);
    }
  }
  sum.silhouette /= counted, sum.frame /= counted, sum.silhouette_pixels /= size_t(counted);
  if (!flying)
    std::printf("the march's own jitter, frame to frame: silhouettes %.2f%%, frame %.2f%%\n",
                100.0 * floor.silhouette / (counted - 1), 100.0 * floor.frame / (counted - 1));
  std::printf("%s: silhouettes (%zu pixels) %.2f%% of the mean luminance, frame relative L1 %.2f%%\n",
              name.c_str(), sum.silhouette_pixels, 100.0 * sum.silhouette, 100.0 * sum.frame);
  return sum;
}

// Measured before the resolve kept the history where its neighbours' history held and read it through
// a Catmull-Rom filter (bilinear, clipped to the 3 x 3 fresh samples' range always): still 5.15% at
// silhouettes and 1.91% over the frame, flying 12.81% and 5.85%; the march's own jitter from frame to
// frame is 0.51% and 0.31%. Those figures and the ones below were taken with the hand-set light model;
// with the fitted one (light_model_fit.glsl) the same resolve measures still 0.92% and 0.45%, flying
// 12.95% and 5.51% (the clouds' contrast is higher), jitter 0.67% and 0.39%; with the light model of
// weighted terms (docs/clouds-light.md) still 1.12% and 0.52%, flying 15.90% and 6.28%, jitter 0.83%
// and 0.45% (greyer undersides against bright edges: more contrast again). Flying, the error is the
// 4-frame renewal's lag, which this resolve does not change: its bounds guard against a regression.
// With the shadow map's columns whole (shadow_map.comp: half the map had none of the cloud above its
// start plane, so half the scene was lit), there is more shadow and more contrast: still 1.06% and
// 0.54%, flying 12.66% and 5.94%.
TEST(CloudsSilhouettes, UpscaledFramesFollowTheFullMarchAtSilhouettes) {
  const EdgeError still = measure(false, 3, "still"), flying = measure(true, 6, "flying");
  EXPECT_GT(still.silhouette_pixels, 500u);
  EXPECT_GT(flying.silhouette_pixels, 500u);
  EXPECT_LT(still.silhouette, 0.015);   // measured 0.75%
  EXPECT_LT(still.frame, 0.008);        // 0.37%
  EXPECT_LT(flying.silhouette, 0.175);  // 11.60% (hand-set light), 12.95% (fitted), 15.90% (terms)
  EXPECT_LT(flying.frame, 0.07);        // 5.19%, 5.51%, 6.28%
}

// The self-shadowing through the shadow cascades against the same march with cascades of four times
// the resolution, a low sun, every pixel marched (issue 35 asked whether the cascades' texels make
// the README images' stair steps). They do not: the difference is under 1% at silhouettes. The steps
// stay with the temporal upscaling off, the shadows off and the march at full resolution, and go
// with the detail noise off: they are the detail noise's erosion of the edges.
TEST(CloudsSilhouettes, TheSelfShadowFollowsAFinerShadowMap) {
  const int w = 128, h = 72;
  auto frame = [&](int map_size) {
    nlohmann::json d = test::noon({{"quality", "high"}, {"temporal_upscaling", false}, {"shadow_map_size", map_size}});
    test::entity_with(d, "atmosphere.Sun")["components"]["atmosphere.Sun"]["elevation_deg"] = 12;
    test::Rendered r = test::render(d, w, h);
    return r.renderer->read_hdr();
  };
  const ImageF coarse = frame(256), fine = frame(1024);
  const EdgeError e = edge_error(coarse, fine);
  write_crop(coarse, "shadow-map-256"), write_crop(fine, "shadow-map-1024");
  std::printf("the 256-texel cascades against 1024: silhouettes (%zu pixels) %.2f%%, frame %.2f%%\n",
              e.silhouette_pixels, 100.0 * e.silhouette, 100.0 * e.frame);
  EXPECT_GT(e.silhouette_pixels, 300u);
  EXPECT_LT(e.silhouette, 0.02);  // measured 0.67%; 1.08% with the columns whole
  EXPECT_LT(e.frame, 0.012);      // 0.40%; 0.72%
}

// The history kept where it holds must still give way where the clouds change: a settled still view,
// then the clouds three times as dense; the next frame (one pixel of each block marched) against a
// full march of it, over the frame. Measured with the history always clipped: 13.93% (now 14.07%).
TEST(CloudsSilhouettes, AChangeOfTheCloudsIsNotKeptAsHistory) {
  const int w = 128, h = 72;
  auto doc = [](bool temporal) {
    return test::noon({{"quality", "high"}, {"temporal_upscaling", temporal}});
  };
  test::Rendered upscaled = test::render(doc(true), w, h), full = test::render(doc(false), w, h);
  for (int f = 1; f < 5; ++f) upscaled.frame(w, h), full.frame(w, h);
  for (test::Rendered* r : {&upscaled, &full}) {
    for (CloudLayer& layer : r->clouds().layers) layer.density_per_m *= 3.0f;
    r->frame(w, h);
  }
  const EdgeError e = edge_error(upscaled.renderer->read_hdr(), full.renderer->read_hdr());
  std::printf("the frame after the clouds changed: silhouettes %.2f%%, frame %.2f%%\n", 100.0 * e.silhouette,
              100.0 * e.frame);
  EXPECT_LT(e.frame, 0.145);
}

}  // namespace
}  // namespace welkin::clouds

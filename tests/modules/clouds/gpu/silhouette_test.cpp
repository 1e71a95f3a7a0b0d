// Silhouettes after the temporal upscaling (issue 35): frames upscaled from one pixel of each block
// per frame (and the pixels next to the last frame's silhouettes) against a march of every pixel of the
// same view, still, turning and flying, at the full march's silhouettes (validation/silhouettes.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "clouds_gpu.h"
#include "clouds_test_support.h"
#include "validation/silhouettes.h"

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

std::unique_ptr<World> peer_world(bool march_silhouettes) {
  std::ifstream in(std::filesystem::path(WELKIN_SOURCE_DIR) / "assets/scenes/clouds-peer.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  test::entity_with(doc, "clouds.VolumetricClouds")["components"]["clouds.VolumetricClouds"]["quality"] =
      "high";
  test::gl_context().make_current();
  auto world = std::make_unique<World>();
  world->modules().add_static(welkin::modules::atmosphere_module());
  world->modules().add_static(welkin::modules::clouds_module());
  load_scene(*world, doc, "clouds-peer.json");
  VolumetricClouds& clouds =
      *world->registry().get<VolumetricClouds>(world->registry().first<VolumetricClouds>());
  clouds.march_silhouettes = march_silhouettes;
  return world;
}

// The march pixels the last frame listed next to its silhouettes (silhouette_march.h), and the work
// groups of its march that the listing counted (GL's indirect dispatch command).
struct ListedPixels {
  uint32_t count = 0, groups = 0;
};

// The peer scene at `high`, 128 x 72 (the march at 64 x 36): frames 0-3 fill the history, `frames` more
// are measured (validation/silhouettes.h), at the silhouettes of the full march's opacity.
SilhouetteError measure(SilhouetteMotion motion, int frames, bool march_silhouettes = true,
                        ListedPixels* listed = nullptr) {
  const int w = 128, h = 72;
  std::unique_ptr<World> upscaled_world = peer_world(march_silhouettes), full_world = peer_world(false);
  Renderer upscaled(*upscaled_world), full(*full_world);
  ImageF a, b;
  const SilhouetteError e =
      measure_silhouettes({*upscaled_world, upscaled}, {*full_world, full}, motion, 4, frames, w, h, &a, &b);
  if (listed) {
    const CloudsGpu& gpu = upscaled_world->resource<CloudsGpu>();
    uint32_t head[4] = {};  // groups x, y, z, count (clouds/silhouette_list.glsl)
    if (gpu.silhouette_list) glGetNamedBufferSubData(gpu.silhouette_list->id(), 0, sizeof(head), head);
    *listed = {head[3], head[0]};
  }
  const std::string name = std::string(motion_name(motion)) + (march_silhouettes ? "" : "-reprojected");
  write_crop(a, name + "-upscaled"), write_crop(b, name + "-full");
  ImageF difference = b;  // |upscaled - full|, x4 against the frame
  for (size_t i = 0; i < b.rgba.size(); ++i)
    difference.rgba[i] = i % 4 == 3 ? 1.0f : std::abs(a.rgba[i] - b.rgba[i]);
  write_crop(difference, name + "-difference", exposure_of(b) * 4.0f);
  std::printf(
      "%s: silhouettes (%zu pixels) %.2f%% of the mean luminance, opacity %.3f; frame relative L1 %.2f%%; "
      "%.0f%% of the march's pixels near a silhouette\n",
      name.c_str(), e.pixels, 100.0 * e.silhouette, e.opacity, 100.0 * e.frame, 100.0 * e.near_silhouette);
  return e;
}

// Measured (llvmpipe, 2026-11-27, on main at cd57934), silhouettes and frame: with the pixels next to
// the last frame's silhouettes listed and marched again (march_silhouettes, 0.6 of opacity over 3 x 3
// pixels, the view moved by a quarter of a pixel) turning 3.19% and 2.10%, flying 7.71% and 5.63%;
// reprojected as before (march_silhouettes off) turning 13.84% and 6.48%, flying 18.47% and 10.63%.
// Still none are listed: 2.99% and 1.58%, as without the pass (the march's jitter from frame to frame,
// which the history holds; the whole-frame pass at 0.5, marching still views too, read 0.23% and 0.41%
// for 1.8-2.2 times the frame). Some 45% of the march's pixels at this size lie near a silhouette (3 x 3
// opacity range over 0.1), 32% at 320 x 180.
TEST(CloudsSilhouettes, UpscaledFramesFollowTheFullMarchAtSilhouettes) {
  ListedPixels still_listed, turning_listed;
  const SilhouetteError still = measure(SilhouetteMotion::still, 3, true, &still_listed),
                        turning = measure(SilhouetteMotion::turning, 6, true, &turning_listed),
                        flying = measure(SilhouetteMotion::flying, 6);
  std::printf("listed: still %u, turning %u pixels in %u groups\n", still_listed.count, turning_listed.count,
              turning_listed.groups);
  EXPECT_GT(still.pixels, 2000u);  // 3651, 3492, 3459 of 8820
  EXPECT_GT(turning.pixels, 2000u);
  EXPECT_GT(flying.pixels, 2000u);
  EXPECT_LT(still.silhouette, 0.035);    // 2.99%
  EXPECT_LT(still.frame, 0.02);          // 1.58%
  EXPECT_LT(turning.silhouette, 0.045);  // 3.19%
  EXPECT_LT(turning.frame, 0.03);        // 2.10%
  EXPECT_LT(flying.silhouette, 0.09);    // 7.71%
  EXPECT_LT(flying.frame, 0.065);        // 5.63%
  // The list: none in a still view; turning, a few of the 6912 pixels the block march left out, and
  // one work group of 64 for every 64 listed or part of them.
  EXPECT_EQ(still_listed.count, 0u);
  EXPECT_GT(turning_listed.count, 50u);
  EXPECT_LT(turning_listed.count, 6912u / 2);
  EXPECT_EQ(turning_listed.groups, (turning_listed.count + 63) / 64);
  // At least halved against the history reprojected as before, measured the same way in this run.
  const SilhouetteError turning_before = measure(SilhouetteMotion::turning, 6, false),
                        flying_before = measure(SilhouetteMotion::flying, 6, false);
  EXPECT_LT(turning.silhouette, 0.5 * turning_before.silhouette);  // 3.19% against 13.84%
  EXPECT_LT(flying.silhouette, 0.5 * flying_before.silhouette);    // 7.71% against 18.47%
  EXPECT_GT(turning_before.silhouette, 0.07);  // 13.84%: the measure still sees the lag it was made for
}

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
// full march of it, over the frame. Measured with the history always clipped: 13.93% (then 14.07%;
// 7.10% with the pixels next to the silhouettes marched again, 5.33% on 3122ad5).
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

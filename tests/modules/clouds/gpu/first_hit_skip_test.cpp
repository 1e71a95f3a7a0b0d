// The march's empty-space skipping from the last frame (src/first_hit_skip.h): frames of a turning,
// flying view with the skipping against the same frames without it, and clouds that appear in front of
// where the last frames saw none (the history told that no ray met a cloud before 100 km).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clouds_test_support.h"
#include "welkin/gfx/compute.h"

namespace welkin::clouds {
namespace {

constexpr int kW = 96, kH = 54;

// Relative L1 of a against b over the frame's colour, and the largest channel difference relative to
// the frame's brightest channel.
struct Difference {
  double l1 = 0.0, worst = 0.0;
};
Difference difference(const ImageF& a, const ImageF& b) {
  double sum = 0.0, total = 0.0, brightest = 0.0, worst = 0.0;
  for (size_t i = 0; i < b.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = std::abs(double(a.rgba[i]) - b.rgba[i]);
    sum += d, total += std::abs(b.rgba[i]);
    brightest = std::max(brightest, double(std::abs(b.rgba[i])));
    worst = std::isnan(d) ? INFINITY : std::max(worst, d);
  }
  return {sum / std::max(total, 1e-30), worst / std::max(brightest, 1e-30)};
}

// The default cumulus at noon, high quality (blocks of 2 x 2), the camera below the layer looking up.
// `silhouettes`: the march at the last frame's silhouettes (on by default).
nlohmann::json doc(bool skip, bool silhouettes = true) {
  nlohmann::json d =
      test::noon({{"quality", "high"}, {"skip_empty_front", skip}, {"march_silhouettes", silhouettes}});
  test::entity_with(d, "core.Camera")["components"]["core.Camera"]["moving_render_scale"] = 1.0;
  return d;
}

void move(test::Rendered& r, int f) {
  r.camera().position_m = {-20.0 * f, -40.0 * f, 100.0 + 5.0 * f};
  r.camera().heading_deg = 210.0f + 1.0f * float(f);
}

// Frames 1-15 (after the first, whole) with and without skipping: a skipped ray's samples fall at
// other places along it, so the frames differ as the march's jitter makes them differ. Measured:
// relative L1 0.17-0.41% (the silhouette test's jitter from frame to frame: 0.39%), the largest channel
// difference 4.0-14.3% of the frame's brightest (at silhouettes).
TEST(CloudsFirstHitSkip, TurningAndFlyingFramesMatchTheMarchWithoutIt) {
  test::Rendered skipped = test::render(doc(true), kW, kH), whole = test::render(doc(false), kW, kH);
  Difference largest, jitter;
  ImageF previous;
  for (int f = 1; f < 16; ++f) {
    for (test::Rendered* r : {&skipped, &whole}) move(*r, f), r->frame(kW, kH);
    const ImageF a = skipped.renderer->read_hdr(), b = whole.renderer->read_hdr();
    const Difference d = difference(a, b);
    largest.l1 = std::max(largest.l1, d.l1), largest.worst = std::max(largest.worst, d.worst);
    std::printf("frame %d: skipping against none, relative L1 %.3f%%, largest %.2f%% of the brightest\n", f,
                100.0 * d.l1, 100.0 * d.worst);
  }
  EXPECT_TRUE(skipped.world->resource<CloudsGpu>().first_hit.valid);
  EXPECT_FALSE(whole.world->resource<CloudsGpu>().first_hit.valid);
  EXPECT_LT(largest.l1, 0.01);
  EXPECT_LT(largest.worst, 0.25);
}

// Clouds that appear in front of where the last frames saw none: both views lose their history (their
// colour: no cloud anywhere), and the skipping's is told that no ray met a cloud before 100 km. The
// next frame with skipping loses most of its clouds (the skipping is used); then the refresh (a whole
// march of one block in eight, whose distances the 3 x 3 neighbourhoods carry a block a frame) finds
// them: the difference to the frames without skipping (which have the resolve's own lag in taking in
// what appeared) shrinks every frame. Measured: 13.3%, 8.6%, 4.8%, 3.4%, 2.2%, 1.7% of the frame. The
// march at silhouettes is off in both: it marches whole rays where the last frame had an edge, which the
// frames without skipping find a frame earlier (their history held the clouds the skipping lost), so
// the difference grew once (12.9%, 14.3%) before it fell faster (2.3%, 0.96%, 0.70%, 0.46%). Without it,
// on 3122ad5: 11.7%, 7.8%, 4.7%, 3.4%, 2.3%, 1.7%.
TEST(CloudsFirstHitSkip, CloudsAppearingInFrontAreFoundAgain) {
  test::Rendered skipped = test::render(doc(true, false), kW, kH),
                 whole = test::render(doc(false, false), kW, kH);
  for (int f = 1; f < 4; ++f)
    for (test::Rendered* r : {&skipped, &whole}) move(*r, f), r->frame(kW, kH);
  for (test::Rendered* r : {&skipped, &whole}) {
    CloudsGpu& gpu = r->world->resource<CloudsGpu>();
    const float clear_sky[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glClearTexImage(gpu.history_color[1 - gpu.history_index]->id(), 0, GL_RGBA, GL_FLOAT, clear_sky);
  }
  CloudsGpu& gpu = skipped.world->resource<CloudsGpu>();
  ASSERT_TRUE(gpu.first_hit.valid);
  const float far_m = 100000.0f;
  glClearTexImage(gpu.first_hit.clear[1 - gpu.history_index]->id(), 0, GL_RED, GL_FLOAT, &far_m);
  std::vector<double> l1;
  for (int f = 4; f < 10; ++f) {
    for (test::Rendered* r : {&skipped, &whole}) move(*r, f), r->frame(kW, kH);
    l1.push_back(difference(skipped.renderer->read_hdr(), whole.renderer->read_hdr()).l1);
    std::printf("frame %d after the clouds appeared: relative L1 %.3f%%\n", f - 3, 100.0 * l1.back());
  }
  EXPECT_GT(l1.front(), 0.05);  // most rays skipped past their clouds
  for (size_t i = 1; i < l1.size(); ++i) EXPECT_LT(l1[i], l1[i - 1]) << "frame " << i + 1;
  EXPECT_LT(l1.back(), 0.025);
}

}  // namespace
}  // namespace welkin::clouds

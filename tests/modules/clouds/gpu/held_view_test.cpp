// A held view's temporal resolve (resolve_pixel.glsl): the history is kept unclipped where the view,
// the field and the light held since the last frame, whoever draws the geometry; where the geometry
// moved (the scene's depth changed under a pixel) the fresh samples around are taken instead.
#include <cstdio>

#include "clouds_test_support.h"
#include "welkin/core/system.h"
#include "welkin/gfx/debug_content.h"

namespace welkin::clouds {
namespace {

// 4 x 4 blocks at the frame's resolution (one pixel of each block marched per frame), a ball (60 m
// in radius) in front of the noon's clouds (300 m along the camera's view) at `ball_m`.
nlohmann::json scene_with_ball(const glm::dvec3& ball_m) {
  nlohmann::json doc = test::noon({{"quality", "custom"},
                                   {"resolution_scale", 1.0},
                                   {"temporal_block", 4},
                                   {"march_silhouettes", false}});
  doc["entities"].push_back(
      {{"name", "ball"},
       {"components",
        {{"core.DebugShape", {{"position_m", {ball_m.x, ball_m.y, ball_m.z}}, {"size_m", {60, 60, 60}}}}}}});
  return doc;
}
constexpr glm::dvec3 kBallInView{-147.7, -255.9, 152.0};  // heading 210, 10 degrees up, 300 m away
constexpr glm::dvec3 kBallBehind{147.7, 255.9, 152.0};    // the same behind the camera

// The clouds' resolved history as the last frame wrote it (colour, transmittance), at the march's size.
ImageF resolved_history(test::Rendered& r) {
  CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  return read_texture_float(*gpu.history_color[1 - gpu.history_index]);
}

// A host's geometry is never known unchanged: its digest changes every frame (welkin/host/sky.cpp),
// where `welkin render`'s debug shapes keep theirs. The same camera and the same geometry still resolve
// the same frames, bit for bit: the view is held from the third frame on in both (the package test's
// host application against `welkin render`, tests/package/check_install.cmake, was 0.76% of its
// pixels more than 3 steps apart when the digest decided it).
TEST(CloudsHeldView, TheSameCameraAndGeometryResolveAlikeWhoeverDrawsThem) {
  const int w = 48, h = 27;
  test::Rendered engine = test::render(scene_with_ball(kBallInView), w, h);
  test::Rendered host = test::render(scene_with_ball(kBallInView), w, h);
  auto serial = std::make_shared<uint64_t>(0);
  host.world->scheduler().add(
      SystemDesc{.name = "test.host_geometry", .stage = Stage::geometry, .run = [serial](SystemContext& sc) {
                   sc.targets->add_geometry(PixelRect{}, ++*serial);
                 }});
  for (int i = 0; i < 4; ++i) engine.frame(w, h), host.frame(w, h);
  const CloudsGpu &e = engine.world->resource<CloudsGpu>(), &o = host.world->resource<CloudsGpu>();
  EXPECT_LE(o.march_state_frames, 1) << "the host's geometry digest changed every frame";
  EXPECT_GE(e.march_state_frames, 4);
  EXPECT_GE(o.view_state_frames, 4) << "held all the same";
  const ImageF a = engine.renderer->read_hdr(), b = host.renderer->read_hdr();
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) differing += a.rgba[i] != b.rgba[i];
  EXPECT_EQ(differing, 0u) << "of " << a.rgba.size() << " values";
}

// Geometry that moves in a held view changes what the march stops at: where the ball stood, the
// history holds no clouds (none lie between the camera and it). The frame after the ball moved out of
// view marched one pixel of each 4 x 4 block; the others take the fresh samples around them, where
// keeping the history would leave the ball's hole for up to 16 frames (and clipping it to the fresh
// samples' range leaves it too: clear sky lies among them). Measured against the same frames of a view
// that never had the ball (the history a held view keeps right), over the pixels the ball hid that hold
// clouds: the transmittance's error at most a quarter of the hole's.
TEST(CloudsHeldView, GeometryThatMovedTakesTheFreshSamples) {
  const int w = 48, h = 27;
  test::Rendered moved = test::render(scene_with_ball(kBallInView), w, h);
  test::Rendered never = test::render(scene_with_ball(kBallBehind), w, h);
  for (int i = 0; i < 5; ++i) moved.frame(w, h), never.frame(w, h);
  const ImageF with_ball = resolved_history(moved);
  ASSERT_GE(moved.world->resource<CloudsGpu>().view_state_frames, 5) << "a held view";
  Registry& reg = moved.world->registry();
  reg.get<DebugShape>(reg.first<DebugShape>())->position_m = kBallBehind;
  moved.frame(w, h), never.frame(w, h);
  EXPECT_GE(moved.world->resource<CloudsGpu>().view_state_frames, 6) << "still held";
  const ImageF after = resolved_history(moved), right = resolved_history(never);
  ASSERT_EQ(after.rgba.size(), right.rgba.size());
  double hole = 0.0, error = 0.0;
  int pixels = 0;
  for (size_t i = 3; i < right.rgba.size(); i += 4) {
    if (!(with_ball.rgba[i] > 0.999f && right.rgba[i] < 0.9f)) continue;  // hidden by the ball, cloudy
    hole += 1.0 - right.rgba[i], error += std::abs(after.rgba[i] - right.rgba[i]), ++pixels;
  }
  std::printf("%d pixels the ball hid: the transmittance's error %.3f, the hole's %.3f\n", pixels,
              error / std::max(pixels, 1), hole / std::max(pixels, 1));
  ASSERT_GE(pixels, 20) << "the ball hid clouds";
  EXPECT_LT(error, 0.25 * hole);
}

}  // namespace
}  // namespace welkin::clouds

// The viewport's cost: the measure-frames verb's arguments and statistics, the moving frames' scale
// kept to a budget, a settled still view, and the steady flight the verb flies.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "model/fly_camera.h"
#include "model/frame_measure.h"
#include "model/viewport_cost.h"
#include "welkin/core/error.h"

namespace {

using namespace welkin::editor;

std::string error_of(const std::vector<std::string>& args) {
  try {
    parse_measure_request(args);
  } catch (const welkin::Error& e) {
    return e.what();
  }
  return "";
}

TEST(MeasureFrames, ParsesStillAndFly) {
  MeasureRequest still = parse_measure_request({"30"});
  EXPECT_EQ(still.frames, 30);
  EXPECT_FALSE(still.fly);
  EXPECT_FALSE(parse_measure_request({"5", "still"}).fly);
  MeasureRequest fly = parse_measure_request({"12", "fly", "150.5", "-10"});
  EXPECT_TRUE(fly.fly);
  EXPECT_EQ(fly.frames, 12);
  EXPECT_DOUBLE_EQ(fly.speed_mps, 150.5);
  EXPECT_DOUBLE_EQ(fly.turn_deg_s, -10.0);
}

TEST(MeasureFrames, RejectsBadArgumentsWithOneClearError) {
  const std::string usage = "usage: measure-frames N [still | fly SPEED_M_S TURN_DEG_S]";
  EXPECT_EQ(error_of({}), usage);
  EXPECT_EQ(error_of({"0"}), usage + " (expected a frame count from 1 to 100000, found '0')");
  EXPECT_EQ(error_of({"-3"}), usage + " (expected a frame count from 1 to 100000, found '-3')");
  EXPECT_EQ(error_of({"1e3"}), usage + " (expected a frame count from 1 to 100000, found '1e3')");
  EXPECT_EQ(error_of({"100001"}), usage + " (expected a frame count from 1 to 100000, found '100001')");
  EXPECT_EQ(error_of({"10", "walk"}), usage + " (expected still or fly, found 'walk')");
  EXPECT_EQ(error_of({"10", "still", "3"}), usage);
  EXPECT_EQ(error_of({"10", "fly", "100"}), usage);
  EXPECT_EQ(error_of({"10", "fly", "fast", "0"}), usage + " (expected a speed from 0 to 1e6 m/s, found 'fast')");
  EXPECT_EQ(error_of({"10", "fly", "-1", "0"}), usage + " (expected a speed from 0 to 1e6 m/s, found '-1')");
  EXPECT_EQ(error_of({"10", "fly", "100", "nan"}), usage + " (expected a turn from -3600 to 3600 deg/s, found 'nan')");
}

TEST(MeasureFrames, SummaryOfAWorkedExample) {
  // Sorted: 10 20 30 40 50 60 70 80 90 100 (given shuffled): mean 55, median (50 + 60) / 2,
  // p90 the 9th of 10 (nearest rank ceil(0.9 * 10) = 9), fps 1000 / 55.
  FrameTimeSummary s = summarize_frame_times({70, 10, 100, 40, 20, 90, 30, 60, 80, 50});
  EXPECT_EQ(s.frames, 10);
  EXPECT_DOUBLE_EQ(s.mean_ms, 55.0);
  EXPECT_DOUBLE_EQ(s.median_ms, 55.0);
  EXPECT_DOUBLE_EQ(s.p90_ms, 90.0);
  EXPECT_DOUBLE_EQ(s.min_ms, 10.0);
  EXPECT_DOUBLE_EQ(s.max_ms, 100.0);
  EXPECT_NEAR(s.fps, 18.1818, 1e-4);
  FrameTimeSummary odd = summarize_frame_times({5, 1, 3});
  EXPECT_DOUBLE_EQ(odd.median_ms, 3.0);
  EXPECT_DOUBLE_EQ(odd.p90_ms, 5.0);  // ceil(2.7) = 3rd
  EXPECT_EQ(summarize_frame_times({}).fps, 0.0);
}

TEST(MeasureFrames, ReportsFramesAndPassesByCost) {
  FrameMeasurement m(MeasureRequest{.frames = 2, .fly = true, .speed_mps = 100, .turn_deg_s = 10});
  m.add(MeasuredFrame{.frame_ms = 100, .passes = {{"clouds.march", 60}, {"tonemap", 2}}, .reduced = true});
  EXPECT_FALSE(m.done());
  m.add(MeasuredFrame{.frame_ms = 300, .passes = {{"tonemap", 4}}, .kept = false});
  m.add(MeasuredFrame{.frame_ms = 1e9});  // past N: ignored
  ASSERT_TRUE(m.done());
  EXPECT_EQ(m.report("viewport 8x6"),
            "measure-frames: 2 frames flying 100.0 m/s turning 10.0 deg/s, viewport 8x6: mean 200.0 ms, median 200.0 ms, "
            "p90 300.0 ms, min 100.0 ms, max 300.0 ms, 5.0 fps; 1 rendered smaller, 0 kept (settled)\n"
            "measure-frames: passes, GPU ms per frame (frames run): clouds.march 30.00 (1) tonemap 3.00 (2)\n");
}

TEST(MovingScale, StartsAtTheCamerasScaleAndKeepsToTheBudget) {
  MovingScale m;  // 100 ms
  EXPECT_FLOAT_EQ(m.for_camera(0.75f), 0.75f);
  for (int i = 0; i < 3; ++i) m.after_moving_frame(250.0);  // over: an eighth down each frame
  EXPECT_FLOAT_EQ(m.for_camera(0.75f), 0.375f);
  for (int i = 0; i < 10; ++i) m.after_moving_frame(250.0);
  EXPECT_FLOAT_EQ(m.for_camera(0.75f), 0.25f);  // no lower than min_scale
  m.after_moving_frame(80.0);                   // within the budget, not well under it: stays
  EXPECT_FLOAT_EQ(m.for_camera(0.75f), 0.25f);
  for (int i = 0; i < 20; ++i) m.after_moving_frame(10.0);
  EXPECT_FLOAT_EQ(m.for_camera(0.75f), 1.0f);  // up to whole while cheap
  MovingScale whole;
  EXPECT_FLOAT_EQ(whole.for_camera(1.0f), 0.5f);  // a camera that renders moving views whole: half
  MovingScale off{.budget_ms = 0};
  off.after_moving_frame(1e6);
  EXPECT_FLOAT_EQ(off.for_camera(0.8f), 0.8f);  // off: the camera's own, whatever the cost
}

TEST(SettledView, KeepsOnlyAfterFramesOfTheSameDigest) {
  SettledView s{.frames = 3};
  EXPECT_FALSE(s.keep(7));
  EXPECT_FALSE(s.keep(7));
  EXPECT_FALSE(s.keep(7));
  EXPECT_TRUE(s.keep(7));  // three rendered alike: the fourth shows the third
  EXPECT_TRUE(s.keep(7));
  EXPECT_FALSE(s.keep(8));  // any change renders at once, and settles again
  EXPECT_FALSE(s.keep(8));
  EXPECT_FALSE(s.keep(8));
  EXPECT_TRUE(s.keep(8));
  SettledView never{.frames = 0};
  for (int i = 0; i < 50; ++i) EXPECT_FALSE(never.keep(1));
}

TEST(FlyCamera, GlideTurnsThenMovesAlongTheView) {
  ViewPose p{{0, 0, 500}, 80.0, 0.0};
  ViewPose q = glide(p, 100.0, 20.0, 0.5);  // 10 deg to east, 50 m
  EXPECT_NEAR(q.heading_deg, 90.0, 1e-12);
  EXPECT_NEAR(q.position_m.x, 50.0, 1e-9);
  EXPECT_NEAR(q.position_m.y, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(q.position_m.z, 500.0);
  EXPECT_NEAR(glide(p, 0.0, -100.0, 1.0).heading_deg, 340.0, 1e-12);  // wraps below north
}

}  // namespace

// Fly camera: look, move along the view, speed from walking pace near the ground to orbit.
#include "model/fly_camera.h"

#include <gtest/gtest.h>

namespace {

using namespace welkin::editor;

TEST(FlyCamera, SpeedScalesWithAltitudeBetweenWalkingAndOrbit) {
  EXPECT_DOUBLE_EQ(fly_speed_mps(2.0), 1.5);       // walking pace
  EXPECT_DOUBLE_EQ(fly_speed_mps(1000.0), 500.0);  // 1 km: half a kilometre a second
  EXPECT_DOUBLE_EQ(fly_speed_mps(-1000.0), 500.0);
  EXPECT_GT(fly_speed_mps(400e3), 7800.0);          // faster than orbit at 400 km
  EXPECT_DOUBLE_EQ(fly_speed_mps(1e12), FlySettings{}.max_speed_mps);
}

TEST(FlyCamera, ForwardFollowsHeadingClockwiseFromNorth) {
  ViewPose p{{0, 0, 1000}, 90.0, 0.0};  // facing east
  ViewPose q = fly(p, FlyInput{.forward = 1, .dt_s = 2});
  EXPECT_NEAR(q.position_m.x, 1000.0, 1e-9);  // 500 m/s for 2 s
  EXPECT_NEAR(q.position_m.y, 0.0, 1e-9);
  EXPECT_NEAR(q.position_m.z, 1000.0, 1e-9);
}

TEST(FlyCamera, DiagonalMotionIsNotFaster) {
  ViewPose p{{0, 0, 2}, 0.0, 0.0};
  ViewPose q = fly(p, FlyInput{.forward = 1, .right = 1, .dt_s = 1});
  EXPECT_NEAR(glm::length(q.position_m - p.position_m), 1.5, 1e-9);
}

TEST(FlyCamera, LookTurnsAndClampsPitch) {
  ViewPose p{{0, 0, 2}, 350.0, 80.0};
  ViewPose q = fly(p, FlyInput{.look_dx_px = 100, .look_dy_px = -1000});
  EXPECT_NEAR(q.heading_deg, 5.0, 1e-9);  // wrapped past north
  EXPECT_DOUBLE_EQ(q.pitch_deg, 89.5);
}

TEST(FlyCamera, NoTimeNoMotion) {
  ViewPose p{{1, 2, 3}, 10.0, 5.0};
  EXPECT_EQ(fly(p, FlyInput{.forward = 1, .dt_s = 0}).position_m, p.position_m);
}

}  // namespace

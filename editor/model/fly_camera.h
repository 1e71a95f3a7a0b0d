#pragma once
// The viewport's fly camera: mouse look and WASD motion at a speed that grows with altitude, so the
// same keys walk at 2 m and cross continents from orbit. Pure math on a pose; the UI feeds input.
#include <glm/glm.hpp>

namespace welkin::editor {

// Where the viewport looks from (the scene camera's pose fields, kept apart from the scene).
struct ViewPose {
  glm::dvec3 position_m{0.0, 0.0, 2.0};  // east, north, up from the scene origin
  double heading_deg = 0;                 // clockwise from north
  double pitch_deg = 0;                   // up is positive
  friend bool operator==(const ViewPose&, const ViewPose&) = default;
};

struct FlyInput {
  double forward = 0, right = 0, up = 0;  // each in [-1, 1] (W/S, D/A, E/Q)
  double look_dx_px = 0, look_dy_px = 0;  // mouse motion while looking
  double speed_multiplier = 1;            // Shift / Ctrl and the wheel scale this
  double dt_s = 0;
};

struct FlySettings {
  double look_deg_per_px = 0.15;
  double speed_per_altitude = 0.5;  // metres per second per metre of altitude
  double min_speed_mps = 1.5;       // walking pace near the ground
  double max_speed_mps = 50000;     // faster than orbit, so planets stay navigable
};

// Base speed at an altitude (metres above the scene's ground plane z = 0; below counts as above).
double fly_speed_mps(double altitude_m, const FlySettings& settings = {});
// Unit vectors (east, north, up) of the pose's view direction and of its right hand.
glm::dvec3 pose_forward(const ViewPose& pose);
glm::dvec3 pose_right(const ViewPose& pose);
// One frame of flight: look first, then move along the new view (up is world up).
ViewPose fly(const ViewPose& pose, const FlyInput& input, const FlySettings& settings = {});
// A steady flight (the measure-frames verb): turn the heading by turn_deg_s, then move along the
// new view at speed_mps, for dt_s.
ViewPose glide(const ViewPose& pose, double speed_mps, double turn_deg_s, double dt_s);

}  // namespace welkin::editor

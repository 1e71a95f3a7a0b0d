#include "model/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace welkin::editor {

double fly_speed_mps(double altitude_m, const FlySettings& s) {
  return std::clamp(std::abs(altitude_m) * s.speed_per_altitude, s.min_speed_mps, s.max_speed_mps);
}

glm::dvec3 pose_forward(const ViewPose& p) {
  double h = glm::radians(p.heading_deg), e = glm::radians(p.pitch_deg);
  return {std::sin(h) * std::cos(e), std::cos(h) * std::cos(e), std::sin(e)};
}

glm::dvec3 pose_right(const ViewPose& p) {
  double h = glm::radians(p.heading_deg);
  return {std::cos(h), -std::sin(h), 0.0};
}

ViewPose fly(const ViewPose& pose, const FlyInput& in, const FlySettings& s) {
  ViewPose out = pose;
  out.heading_deg = std::fmod(pose.heading_deg + in.look_dx_px * s.look_deg_per_px, 360.0);
  if (out.heading_deg < 0) out.heading_deg += 360.0;
  // Stop short of straight up/down, where heading stops meaning anything.
  out.pitch_deg = std::clamp(pose.pitch_deg - in.look_dy_px * s.look_deg_per_px, -89.5, 89.5);
  glm::dvec3 move = pose_forward(out) * std::clamp(in.forward, -1.0, 1.0) + pose_right(out) * std::clamp(in.right, -1.0, 1.0) +
                    glm::dvec3(0, 0, 1) * std::clamp(in.up, -1.0, 1.0);
  double length = glm::length(move);
  if (length > 1e-9 && in.dt_s > 0) {
    double speed = fly_speed_mps(pose.position_m.z, s) * std::max(in.speed_multiplier, 0.0);
    out.position_m += move / std::max(length, 1.0) * speed * in.dt_s;
  }
  return out;
}

ViewPose glide(const ViewPose& pose, double speed_mps, double turn_deg_s, double dt_s) {
  ViewPose out = pose;
  out.heading_deg = std::fmod(pose.heading_deg + turn_deg_s * dt_s, 360.0);
  if (out.heading_deg < 0) out.heading_deg += 360.0;
  out.position_m += pose_forward(out) * speed_mps * dt_s;
  return out;
}

}  // namespace welkin::editor

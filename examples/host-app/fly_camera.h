#pragma once
// The host's own camera: a position in metres (x east, y north, z up, double precision), a heading
// clockwise from north and a pitch; keys fly it. Nothing of it is Welkin's.
#include <glm/glm.hpp>

struct GLFWwindow;

struct FlyCamera {
  glm::dvec3 position{0.0, 0.0, 2.0};
  double heading_deg = 0.0, pitch_deg = 0.0;
  double vertical_fov_deg = 60.0, near_m = 0.5;
  double far_m = 20000.0;  // forward depth only; reversed depth has no far plane

  glm::dvec3 forward() const;
  glm::dvec3 right() const;
  // World to eye (looking down -z), and the same rotation alone (for camera-relative drawing).
  glm::dmat4 view() const;
  glm::mat4 rotation() const;
  // Reversed: infinite far plane, depth 1 at near and 0 at infinity (glClipControl ZERO_TO_ONE).
  // Forward: OpenGL's default [-1, 1] clip depth, 0 at near and 1 at far_m.
  glm::mat4 projection(double aspect, bool reversed_depth) const;
  // WASD: along the ground, Q/E: down/up, arrows: turn, shift: ten times faster.
  void fly(GLFWwindow* window, double dt_s);
};

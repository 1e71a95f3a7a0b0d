#pragma once
// The camera component and the per-frame view derived from it. World positions are doubles in a
// local east-north-up frame at the scene origin (x east, y north, z up, metres); the GPU sees only
// positions relative to the camera, in floats, so a camera 10 000 km out is as stable as at 2 m.
// Projection is reversed-Z with an infinite far plane.
#include <glm/glm.hpp>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin {

enum class Tonemapper : int { aces = 0, agx = 1, linear = 2 };
enum class ExposureMode : int { ev100 = 0, manual = 1 };

struct Camera {
  static constexpr std::string_view kTypeName = "core.Camera";
  glm::dvec3 position_m{0.0, 0.0, 2.0};
  float heading_deg = 0.0f;  // clockwise from north
  float pitch_deg = 0.0f;    // up is positive
  float roll_deg = 0.0f;
  float vertical_fov_deg = 60.0f;
  float near_m = 0.1f;
  ExposureMode exposure_mode = ExposureMode::ev100;
  float ev100 = 14.0f;      // sunny-16 daylight is about 15
  float exposure = 1.0f;    // multiplier, used when exposure_mode is manual
  Tonemapper tonemapper = Tonemapper::aces;
  // While the view moves (a frame not rendered alone whose view differs from the last frame's): the
  // fraction of the output's width and height rendered, upscaled to it. A still view, and every frame
  // rendered alone (`welkin render`, sequences), is rendered whole. 1: always whole.
  float moving_render_scale = 1.0f;
};
void describe(TypeBuilder<Camera>& t);

// What render passes need of the camera this frame.
struct FrameView {
  int width = 1, height = 1;
  glm::dvec3 camera_position_m{0.0};
  glm::mat4 view{1.0f};            // rotation only: camera-relative world to view
  glm::mat4 projection{1.0f};      // reversed-Z, infinite far
  glm::mat4 view_projection{1.0f};
  glm::mat4 inverse_view_projection{1.0f};
  glm::vec3 forward{0, 1, 0}, right{1, 0, 0}, up{0, 0, 1};
  float vertical_fov_rad = 1.0f;
  float near_m = 0.1f;
  float exposure = 1.0f;  // linear multiplier applied before tone mapping
  Tonemapper tonemapper = Tonemapper::aces;
};

FrameView make_frame_view(const Camera& camera, int width, int height);
// A view from an orthonormal basis (right, up, forward in the scene frame), with the projection above;
// exposure and tone mapping left at their defaults.
FrameView make_frame_view(const glm::dvec3& position_m, const glm::vec3& right, const glm::vec3& up,
                          const glm::vec3& forward, float vertical_fov_rad, float near_m, int width,
                          int height);
// Lagarde & de Rousiers: exposure = 1 / (1.2 * 2^EV100) for a saturation-based sensor.
float exposure_from_ev100(float ev100);
// World-space (camera-relative) direction of a pixel centre; y grows downwards in images.
glm::vec3 pixel_direction(const FrameView& view, double x, double y);

// Pixels [x0, x1) x [y0, y1) in GL's window coordinates (origin at the bottom left).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool covers(int width, int height) const { return x0 <= 0 && y0 <= 0 && x1 >= width && y1 >= height; }
  void include(const PixelRect& r);  // the smallest rectangle holding both
  bool operator==(const PixelRect&) const = default;
};
// Every pixel a camera-relative box can cover, conservatively (a pixel of margin), its part nearer
// than the near plane cut off: empty when all of it is, the whole view when it cannot be bounded.
PixelRect screen_rect(const FrameView& view, const glm::vec3& lo, const glm::vec3& hi);

}  // namespace welkin

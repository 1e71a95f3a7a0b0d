#include "welkin/gfx/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace welkin {

void describe(TypeBuilder<Camera>& t) {
  t.tooltip("Perspective camera; position in the scene's east-north-up frame");
  t.field("position_m", &Camera::position_m)
      .unit("m")
      .range(-1e9, 1e9)
      .tooltip("Position (east, north, up) from the scene origin");
  t.field("heading_deg", &Camera::heading_deg)
      .unit("deg")
      .range(-720, 720)
      .tooltip("Heading, clockwise from north");
  t.field("pitch_deg", &Camera::pitch_deg).unit("deg").range(-90, 90).tooltip("Pitch above the horizontal");
  t.field("roll_deg", &Camera::roll_deg).unit("deg").range(-180, 180);
  t.field("vertical_fov_deg", &Camera::vertical_fov_deg)
      .unit("deg")
      .range(1, 170)
      .tooltip("Vertical field of view");
  t.field("near_m", &Camera::near_m)
      .unit("m")
      .range(1e-3, 1e5)
      .tooltip("Near plane; the far plane is at infinity (reversed Z)");
  t.field("exposure_mode", &Camera::exposure_mode).values({{"ev100", 0}, {"manual", 1}});
  t.field("ev100", &Camera::ev100)
      .unit("EV")
      .range(-12, 24)
      .tooltip("Exposure value at ISO 100 (daylight ~15, sunset ~12, moonlight ~-2)");
  t.field("exposure", &Camera::exposure).range(0, 1e6).tooltip("Linear exposure multiplier (manual mode)");
  t.field("tonemapper", &Camera::tonemapper)
      .values({{"aces", 0}, {"agx", 1}, {"linear", 2}})
      .tooltip("Tone-mapping curve");
  t.field("moving_render_scale", &Camera::moving_render_scale)
      .range(0.25, 1)
      .tooltip(
          "While the view moves: fraction of the width and height rendered (upscaled); still views render "
          "whole");
}

float exposure_from_ev100(float ev100) { return 1.0f / (1.2f * std::exp2(ev100)); }

FrameView make_frame_view(const Camera& c, int width, int height) {
  double h = glm::radians(double(c.heading_deg)), p = glm::radians(double(c.pitch_deg)),
         r = glm::radians(double(c.roll_deg));
  glm::dvec3 fwd(std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), std::sin(p));
  glm::dvec3 right0(std::cos(h), -std::sin(h), 0.0);
  glm::dvec3 up0 = glm::cross(right0, fwd);
  glm::dvec3 right = std::cos(r) * right0 + std::sin(r) * up0;
  glm::dvec3 up = glm::cross(right, fwd);
  FrameView v = make_frame_view(c.position_m, glm::vec3(right), glm::vec3(up), glm::vec3(fwd),
                                glm::radians(c.vertical_fov_deg), c.near_m, width, height);
  v.exposure = c.exposure_mode == ExposureMode::ev100 ? exposure_from_ev100(c.ev100) : c.exposure;
  v.tonemapper = c.tonemapper;
  return v;
}

FrameView make_frame_view(const glm::dvec3& position_m, const glm::vec3& right, const glm::vec3& up,
                          const glm::vec3& forward, float vertical_fov_rad, float near_m, int width,
                          int height) {
  FrameView v;
  v.width = width;
  v.height = height;
  v.camera_position_m = position_m;
  v.forward = forward;
  v.right = right;
  v.up = up;
  glm::mat4 view(1.0f);
  view[0] = glm::vec4(v.right.x, v.up.x, -v.forward.x, 0);
  view[1] = glm::vec4(v.right.y, v.up.y, -v.forward.y, 0);
  view[2] = glm::vec4(v.right.z, v.up.z, -v.forward.z, 0);
  v.view = view;
  v.vertical_fov_rad = vertical_fov_rad;
  v.near_m = near_m;
  // Reversed-Z infinite projection with [0,1] clip depth (glClipControl ZERO_TO_ONE): z_ndc = near / -z_view.
  float f = 1.0f / std::tan(v.vertical_fov_rad * 0.5f);
  float aspect = float(width) / float(height);
  glm::mat4 proj(0.0f);
  proj[0][0] = f / aspect;
  proj[1][1] = f;
  proj[2][3] = -1.0f;
  proj[3][2] = near_m;
  v.projection = proj;
  v.view_projection = proj * view;
  v.inverse_view_projection = glm::inverse(v.view_projection);
  return v;
}

glm::vec3 pixel_direction(const FrameView& v, double x, double y) {
  double ndc_x = (x / v.width) * 2.0 - 1.0;
  double ndc_y = 1.0 - (y / v.height) * 2.0;
  double t = std::tan(v.vertical_fov_rad * 0.5);
  double aspect = double(v.width) / v.height;
  glm::dvec3 d =
      glm::dvec3(v.forward) + ndc_x * t * aspect * glm::dvec3(v.right) + ndc_y * t * glm::dvec3(v.up);
  return glm::vec3(glm::normalize(d));
}

void PixelRect::include(const PixelRect& r) {
  if (r.empty()) return;
  if (empty()) {
    *this = r;
    return;
  }
  x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0), x1 = std::max(x1, r.x1), y1 = std::max(y1, r.y1);
}

PixelRect screen_rect(const FrameView& view, const glm::vec3& lo, const glm::vec3& hi) {
  const PixelRect whole{0, 0, view.width, view.height};
  glm::vec4 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] =
        view.view_projection * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f);
  // The box's part in front of the near plane (clip w >= near in the reversed-Z infinite projection)
  // is the hull of the corners there and of the edges' crossings of the plane.
  const float near = view.near_m;
  glm::vec2 lo_ndc(INFINITY), hi_ndc(-INFINITY);
  auto add = [&](const glm::vec4& p) {
    const glm::vec2 ndc = glm::vec2(p) / p.w;
    lo_ndc = glm::min(lo_ndc, ndc), hi_ndc = glm::max(hi_ndc, ndc);
  };
  for (int i = 0; i < 8; ++i) {
    if (c[i].w >= near) add(c[i]);
    for (int axis = 1; axis < 8; axis <<= 1) {  // each edge once, from its corner with the bit clear
      if (i & axis) continue;
      const glm::vec4 &a = c[i], &b = c[i | axis];
      if ((a.w < near) != (b.w < near)) add(glm::mix(a, b, (near - a.w) / (b.w - a.w)));
    }
  }
  if (!(lo_ndc.x <= hi_ndc.x && lo_ndc.y <= hi_ndc.y)) {
    const bool all_behind = std::all_of(c, c + 8, [&](const glm::vec4& p) { return p.w < near; });
    return all_behind ? PixelRect{} : whole;  // NaN corners cannot be bounded
  }
  auto to_pixels = [](float ndc, int size, float rounding) {
    const float px = rounding + (0.5f * ndc + 0.5f) * float(size);
    return int(std::clamp(px, -1.0f, float(size) + 1.0f));
  };
  PixelRect r{to_pixels(lo_ndc.x, view.width, -1.0f), to_pixels(lo_ndc.y, view.height, -1.0f),
              to_pixels(hi_ndc.x, view.width, 2.0f), to_pixels(hi_ndc.y, view.height, 2.0f)};
  r.x0 = std::max(r.x0, 0), r.y0 = std::max(r.y0, 0);
  r.x1 = std::min(r.x1, view.width), r.y1 = std::min(r.y1, view.height);
  return r.empty() ? PixelRect{} : r;
}

}  // namespace welkin

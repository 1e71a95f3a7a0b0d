#include "welkin/atmosphere/ground_region.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace welkin::atmosphere {

bool ray_meets_ground(const FrameBlock& u, double x, double y) {
  const glm::dvec4 far = glm::dmat4(u.inverse_view_projection) * glm::dvec4(x, y, 0.5, 1.0);
  const glm::dvec3 d = glm::normalize(glm::dvec3(far) / far.w);
  const glm::dvec3 o(u.camera_km);
  const double radius = u.medium.bottom_radius_km;
  // |o + t d| = radius for some t > 0: below the ground every ray meets it; above, the ray must point
  // toward the planet and pass within the radius of its centre.
  const double c = (glm::length(o) - radius) * (glm::length(o) + radius);
  if (c <= 0.0) return true;
  const double b = glm::dot(o, d);
  return b < 0.0 && b * b - c >= 0.0;
}

PixelRect ground_pixel_rect(const FrameBlock& u, int width, int height) {
  if (width <= 0 || height <= 0) return {};
  constexpr int kCells = 32;  // grid cells across each axis
  int x0 = width, y0 = height, x1 = -1, y1 = -1;
  const auto test = [&](double px, double py) {  // a point in pixels
    if (!ray_meets_ground(u, px / width * 2.0 - 1.0, py / height * 2.0 - 1.0)) return;
    x0 = std::min(x0, int(px)), y0 = std::min(y0, int(py));
    x1 = std::max(x1, int(px)), y1 = std::max(y1, int(py));
  };
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) test(double(i) * width / kCells, double(j) * height / kCells);
  // The border pixel by pixel: a sliver of ground along an edge between two grid points.
  for (int i = 0; i < width; ++i) test(i + 0.5, 0.5), test(i + 0.5, height - 0.5);
  for (int j = 0; j < height; ++j) test(0.5, j + 0.5), test(width - 0.5, j + 0.5);
  // Toward the planet's centre: a planet far away may be smaller than a grid cell.
  const glm::dvec4 centre = glm::dmat4(u.view_projection) * glm::dvec4(-glm::dvec3(u.camera_km), 0.0);
  if (centre.w > 0.0) {
    const double nx = centre.x / centre.w, ny = centre.y / centre.w;
    if (std::abs(nx) <= 1.0 && std::abs(ny) <= 1.0) test((nx * 0.5 + 0.5) * width, (ny * 0.5 + 0.5) * height);
  }
  if (x1 < 0) return {};
  const int mx = width / kCells + 2, my = height / kCells + 2;
  return {std::max(x0 - mx, 0), std::max(y0 - my, 0), std::min(x1 + mx + 1, width),
          std::min(y1 + my + 1, height)};
}

}  // namespace welkin::atmosphere

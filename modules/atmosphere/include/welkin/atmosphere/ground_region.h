#pragma once
// The part of the frame where view rays can meet the planet's ground: the sky pass shades the ground
// through the light environment (cloud shadows) only there. On a software rasteriser a shader pays for
// a branch in every pixel of a group whenever one pixel takes it, so the ground's shading is a second
// draw limited to this rectangle rather than a branch in the sky's shader. Pure CPU.
#include "welkin/atmosphere/gpu.h"

namespace welkin::atmosphere {

// Pixels [x0, x1) x [y0, y1), GL window coordinates (row 0 at the bottom); empty when no ray of the
// frame meets the ground.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// Conservative: every pixel whose ray (through its centre) meets the ground sphere lies inside. The
// rays through a grid of the frame and along its border are tested, and the box around those that
// meet the ground is widened by a grid cell (the ground's image is convex: the projection of a ball).
PixelRect ground_pixel_rect(const GpuUniforms& u, int width, int height);

// Whether the ray through normalised device coordinates (x, y) meets the ground sphere.
bool ray_meets_ground(const GpuUniforms& u, double x, double y);

}  // namespace welkin::atmosphere

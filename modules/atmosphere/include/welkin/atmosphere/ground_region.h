#pragma once
// The part of the frame where view rays can meet the planet's ground: the sky pass shades the ground
// through the light environment (cloud shadows) only there. On a software rasteriser a shader pays for
// a branch in every pixel of a group whenever one pixel takes it, so the ground's shading is a second
// draw limited to this rectangle rather than a branch in the sky's shader. Pure CPU.
#include "welkin/atmosphere/gpu.h"
#include "welkin/gfx/camera.h"

namespace welkin::atmosphere {

// Conservative: every pixel whose ray (through its centre) meets the ground sphere lies inside. The
// rays through a grid of the frame and along its border are tested, and the box around those that
// meet the ground is widened by a grid cell (the ground's image is convex: the projection of a ball).
// Empty when no ray of the frame meets the ground.
PixelRect ground_pixel_rect(const FrameBlock& u, int width, int height);

// Whether the ray through normalised device coordinates (x, y) meets the ground sphere.
bool ray_meets_ground(const FrameBlock& u, double x, double y);

}  // namespace welkin::atmosphere

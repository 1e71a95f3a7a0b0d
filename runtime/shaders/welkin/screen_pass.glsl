#pragma once
// A full-screen pass in its compute form (welkin/gfx/screen_pass.h): one invocation per pixel of the
// rectangle [u_pixel_origin, u_pixel_end), in tiles of 8 x 8 (kScreenTileX, kScreenTileY).
layout(local_size_x = 8, local_size_y = 8) in;
uniform ivec2 u_pixel_origin;
uniform ivec2 u_pixel_end;

// This invocation's pixel, and whether it lies inside the rectangle (the last tiles overhang it).
bool screen_pixel(out ivec2 pixel) {
  pixel = u_pixel_origin + ivec2(gl_GlobalInvocationID.xy);
  return all(lessThan(pixel, u_pixel_end));
}

// The pixel's centre in normalised device coordinates, as a full-screen triangle interpolates it.
vec2 screen_ndc(ivec2 pixel, ivec2 size) { return (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0; }

// The tone map as a compute pass (welkin/tonemap_pixel.glsl) into the 8-bit output.
#include "welkin/screen_pass.glsl"
#include "welkin/tonemap_pixel.glsl"
layout(rgba8, binding = 0) uniform writeonly image2D o_output;
void main() {
  ivec2 pixel;
  if (screen_pixel(pixel)) imageStore(o_output, pixel, tonemap_pixel(vec2(pixel) + 0.5));
}

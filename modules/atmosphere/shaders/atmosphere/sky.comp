// The sky as a compute pass (atmosphere/sky_pixel.glsl): over the whole frame, with the discs
// (ATM_SKY_DISCS: two dot products a pixel, where the fragment form draws them on squares); or, with
// ATM_SKY_GROUND_ONLY, the ground's light over a rectangle, on the pixels no geometry covers (depth 0,
// reversed Z) whose rays meet the ground.
#include "welkin/screen_pass.glsl"
#include "atmosphere/sky_pixel.glsl"
#include "atmosphere/sky_direction.glsl"
#ifndef ATM_RADIANCE_FORMAT
#define ATM_RADIANCE_FORMAT rgba16f  // rgba32f where the renderer measures (full precision)
#endif
layout(ATM_RADIANCE_FORMAT, binding = 0) uniform writeonly image2D o_color;
#if ATM_SKY_GROUND_ONLY
layout(binding = 0) uniform sampler2D u_depth;
#endif

void main() {
  ivec2 pixel;
  if (!screen_pixel(pixel)) return;
#if ATM_SKY_GROUND_ONLY
  if (texelFetch(u_depth, pixel, 0).r > 0.0) return;
#endif
  vec4 color;
  if (sky_pixel(sky_direction(screen_ndc(pixel, imageSize(o_color))), color))
    imageStore(o_color, pixel, color);
}

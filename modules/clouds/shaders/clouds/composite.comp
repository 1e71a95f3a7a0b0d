// The clouds' composite as a compute pass (clouds/composite_pixel.glsl), in place: the frame's colour
// c becomes over + over.a * c, as the fragment form's blend (one, source alpha) makes it.
#include "welkin/screen_pass.glsl"
#include "clouds/composite_pixel.glsl"
#ifndef CLOUDS_RADIANCE_FORMAT
#define CLOUDS_RADIANCE_FORMAT rgba16f
#endif
layout(CLOUDS_RADIANCE_FORMAT, binding = 0) uniform image2D u_color;
void main() {
  ivec2 pixel;
  if (!screen_pixel(pixel)) return;
  vec4 over = clouds_over(screen_ndc(pixel, imageSize(u_color)) * 0.5 + 0.5);
  vec4 c = imageLoad(u_color, pixel);
  imageStore(u_color, pixel, over + over.a * c);
}

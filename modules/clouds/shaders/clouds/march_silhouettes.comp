// The march at the pixels next to a silhouette as a compute pass (clouds/march_silhouettes_pixel.glsl),
// in tiles of welkin/screen_pass.glsl.
#include "welkin/screen_pass.glsl"
#include "clouds/march_silhouettes_pixel.glsl"
layout(rgba16f, binding = 0) uniform writeonly image2D o_color;
void main() {
  ivec2 pixel;
  if (!screen_pixel(pixel)) return;
  imageStore(o_color, pixel, clouds_march_silhouette(pixel));
}

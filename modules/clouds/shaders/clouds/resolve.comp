// The clouds' temporal resolve as a compute pass (clouds/resolve_pixel.glsl), in tiles of
// welkin/screen_pass.glsl.
#include "welkin/screen_pass.glsl"
#include "clouds/resolve_pixel.glsl"
layout(rgba16f, binding = 0) uniform writeonly image2D o_color;
layout(r32f, binding = 3) uniform writeonly image2D o_depth;
#if CLOUDS_WITH_CLUSTERS
layout(rgba16f, binding = 1) uniform writeonly image2D o_with_clusters;
#endif
#if CLOUDS_CLEAR
layout(r32f, binding = 2) uniform writeonly image2D o_clear;
#endif
void main() {
  ivec2 pixel;
  if (!screen_pixel(pixel)) return;
  float depth;
  vec4 color = resolved(pixel, screen_ndc(pixel, imageSize(o_color)), depth);
  imageStore(o_color, pixel, color);
  imageStore(o_depth, pixel, vec4(depth));
#if CLOUDS_WITH_CLUSTERS
  imageStore(o_with_clusters, pixel, with_clusters(pixel, color));
#endif
#if CLOUDS_CLEAR
  imageStore(o_clear, pixel, vec4(resolved_clear(pixel)));
#endif
}

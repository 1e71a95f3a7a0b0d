// The march again at the pixels that silhouettes_mark.comp listed, at the march's whole resolution, one
// invocation per listed pixel (clouds/silhouette_list.glsl): every invocation of a work group marches,
// where a pass over the whole frame would leave most of them idle beside the few that march (a GPU's
// warps, llvmpipe's SIMD lanes). Writes into the target the marking cleared to -1 (the resolve
// reprojects the history there: resolve_pixel.glsl).
#include "clouds/silhouette_list.glsl"
layout(local_size_x = CLOUDS_SILHOUETTE_GROUP) in;
#include "clouds/march_pixel.glsl"
layout(rgba16f, binding = 0) uniform writeonly image2D o_color;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= sl_count) return;
  ivec2 pixel = ivec2(sl_pixels[i] & 0xffffu, sl_pixels[i] >> 16);
  clouds_load();
  vec4 color;
  vec3 distances;
  clouds_march_pixel(pixel, color, distances);
  imageStore(o_color, pixel, color);
}

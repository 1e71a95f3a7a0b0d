// Lists the march pixels next to the last frame's silhouettes (clouds/silhouettes_mark.glsl), in tiles
// of welkin/screen_pass.glsl: each marked pixel is appended to the list (clouds/silhouette_list.glsl),
// and every CLOUDS_SILHOUETTE_GROUP-th one adds a work group to the march over it.
#include "welkin/screen_pass.glsl"
#include "clouds/silhouette_list.glsl"
#include "clouds/silhouettes_mark.glsl"
void main() {
  ivec2 pixel;
  if (!screen_pixel(pixel) || !clouds_at_silhouette(pixel)) return;
  uint i = atomicAdd(sl_count, 1u);
  sl_pixels[i] = uint(pixel.x) | (uint(pixel.y) << 16);
  if (i % uint(CLOUDS_SILHOUETTE_GROUP) == 0u) atomicAdd(sl_groups_x, 1u);
}

// The clouds' march as a compute pass over the march's target (clouds/march_pixel.glsl), in tiles of
// welkin/screen_pass.glsl.
#include "welkin/screen_pass.glsl"
#include "clouds/march_pixel.glsl"
layout(rgba16f, binding = 0) uniform writeonly image2D o_color;
layout(rgba32f, binding = 1) uniform writeonly image2D o_distance;
void main() {
  ivec2 target;
  if (!screen_pixel(target)) return;
  clouds_load();
  vec4 color;
  vec3 distances;
  clouds_march_pixel(target * u_stride_offset.x + u_stride_offset.yz, color, distances);
  imageStore(o_color, target, color);
  imageStore(o_distance, target, vec4(distances, 0.0));
}

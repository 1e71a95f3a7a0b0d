// The clouds' march as a fragment pass over the march's target (clouds/march_pixel.glsl).
#include "clouds/march_pixel.glsl"
in vec2 v_ndc;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_distance;
void main() {
  clouds_load();
  vec3 distances;
  clouds_march_pixel(ivec2(gl_FragCoord.xy) * u_stride_offset.x + u_stride_offset.yz, o_color, distances);
  o_distance = vec4(distances, 0.0);
}

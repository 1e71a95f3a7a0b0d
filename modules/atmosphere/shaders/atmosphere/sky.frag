// The sky as a fragment pass (atmosphere/sky_pixel.glsl), over sky.vert's full-screen triangle or the
// discs' squares.
#include "atmosphere/sky_pixel.glsl"
in vec3 v_dir;
out vec4 o_color;

void main() {
  vec4 color;
  if (!sky_pixel(v_dir, color)) discard;
  o_color = color;
}

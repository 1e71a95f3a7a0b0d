// The tone map as a fragment pass (welkin/tonemap_pixel.glsl).
#include "welkin/tonemap_pixel.glsl"
out vec4 o_color;
void main() { o_color = tonemap_pixel(gl_FragCoord.xy); }

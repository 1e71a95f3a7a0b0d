#include "pattern_common.glsl"
out vec4 o_color;
void main() { o_color = pattern(ivec2(gl_FragCoord.xy)); }

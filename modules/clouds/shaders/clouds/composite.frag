// The clouds' composite as a fragment pass (clouds/composite_pixel.glsl); the blend (one, source
// alpha) scales what lies behind.
#include "clouds/composite_pixel.glsl"
in vec2 v_ndc;
layout(location = 0, index = 0) out vec4 o_color;
void main() { o_color = clouds_over(v_ndc * 0.5 + 0.5); }

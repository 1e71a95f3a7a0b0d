// The march at the pixels next to a silhouette as a fragment pass (clouds/march_silhouettes_pixel.glsl).
#include "clouds/march_silhouettes_pixel.glsl"
in vec2 v_ndc;
layout(location = 0) out vec4 o_color;
void main() { o_color = clouds_march_silhouette(ivec2(gl_FragCoord.xy)); }

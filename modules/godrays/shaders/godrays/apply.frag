// The god rays and the haze applied to the frame through blending. With haze: frame x T_haze +
// (haze light - shafts) (source 1, destination source alpha). Shafts alone: frame - shafts (reverse
// subtraction of 1 x source). On llvmpipe the blending alone costs 0.7 copies of the frame, the
// shafts' bilinear read another 0.9 (a compute pass storing the frame in place cost 2.5 in all).
in vec2 v_ndc;
layout(location = 0, index = 0) out vec4 o_color;
#include "godrays/apply.glsl"

void main() {
  vec4 c = haze_and_shafts(v_ndc, ivec2(gl_FragCoord.xy));
#if GODRAYS_HAZE
  o_color = c;
#else
  o_color = vec4(-c.rgb, 0.0);
#endif
}

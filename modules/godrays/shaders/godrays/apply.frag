// The god rays and the haze applied to the frame through blending. With haze: frame x T_haze +
// (haze light - shafts) (source 1, destination source alpha). Shafts alone: frame - shafts (reverse
// subtraction of 1 x source), which llvmpipe blends into the half-float frame at 1.1 copies of it
// against 1.6 for the general form (and a compute pass storing in place, 2.5).
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

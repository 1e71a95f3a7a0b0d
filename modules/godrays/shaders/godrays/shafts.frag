// The shafts as a fragment pass over the loss texture (godrays/shafts.glsl).
#include "godrays/shafts.glsl"
in vec2 v_ndc;
layout(location = 0) out vec4 o_loss;
void main() { o_loss = shafts_texel(v_ndc, gl_FragCoord.xy); }

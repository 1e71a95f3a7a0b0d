// The shafts as a compute pass over the loss texture (godrays/shafts.glsl).
#include "welkin/screen_pass.glsl"
#include "godrays/shafts.glsl"
layout(GODRAYS_LOSS_FORMAT, binding = 0) uniform writeonly image2D o_loss;
void main() {
  ivec2 texel;
  if (screen_pixel(texel))
    imageStore(o_loss, texel, shafts_texel(screen_ndc(texel, imageSize(o_loss)), vec2(texel) + 0.5));
}

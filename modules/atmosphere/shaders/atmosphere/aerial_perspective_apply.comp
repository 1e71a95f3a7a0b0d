// Deferred aerial perspective on opaque geometry as a compute pass: colour * T + in-scattering, in
// place, on the pixels geometry covers (depth above 0, reversed Z) inside the pass's rectangle.
#include "welkin/screen_pass.glsl"
#include "atmosphere/aerial_perspective.glsl"
#ifndef ATM_RADIANCE_FORMAT
#define ATM_RADIANCE_FORMAT rgba16f
#endif
layout(ATM_RADIANCE_FORMAT, binding = 0) uniform image2D u_color;
layout(binding = 0) uniform sampler2D u_depth;

void main() {
  ivec2 pixel;
  if (!screen_pixel(pixel)) return;
  float depth = texelFetch(u_depth, pixel, 0).r;
  if (depth <= 0.0) return;
  vec4 p = atm.inverse_view_projection * vec4(screen_ndc(pixel, imageSize(u_color)), depth, 1.0);
  AtmosphereAerialPerspective ap = atmosphere_aerial_perspective(p.xyz / p.w);
  vec4 c = imageLoad(u_color, pixel);
  imageStore(u_color, pixel, vec4(c.rgb * ap.transmittance + atm_fit_half(ap.inscattering), c.a));
}

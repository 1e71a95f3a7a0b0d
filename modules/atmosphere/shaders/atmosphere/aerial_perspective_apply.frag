// Deferred aerial perspective on opaque geometry: colour * T + in-scattering, by dual-source
// blending (GL_ONE, GL_SRC1_COLOR) so the pass never reads the colour target it writes. The depth
// test (the triangle at infinity, GL_LESS) keeps it off the sky, so sky pixels cost nothing.
#include "atmosphere/aerial_perspective.glsl"
in vec2 v_ndc;
layout(location = 0, index = 0) out vec4 o_inscattering;
layout(location = 0, index = 1) out vec4 o_transmittance;
uniform sampler2D u_depth;

void main() {
  float depth = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
  vec4 p = atm.inverse_view_projection * vec4(v_ndc, depth, 1.0);
  AtmosphereAerialPerspective ap = atmosphere_aerial_perspective(p.xyz / p.w);
  o_inscattering = vec4(atm_fit_half(ap.inscattering), 0.0);
  o_transmittance = vec4(ap.transmittance, 1.0);
}

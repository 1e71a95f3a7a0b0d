#include "welkin/tonemap.glsl"
in vec2 v_ndc;
out vec4 o_color;
uniform sampler2D u_hdr;
uniform float u_exposure;
uniform int u_tonemapper;  // 0 ACES, 1 AgX, 2 linear (clamped)
void main() {
  vec3 hdr = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb * u_exposure;
  // A NaN or negative upstream must not turn into a black or white block on screen.
  hdr = clamp(hdr, vec3(0.0), vec3(65504.0));
  vec3 display = u_tonemapper == 0 ? tonemap_aces(hdr) : u_tonemapper == 1 ? tonemap_agx(hdr) : clamp(hdr, 0.0, 1.0);
  o_color = vec4(linear_to_srgb(display), 1.0);
}
